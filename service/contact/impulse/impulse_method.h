// The impulse method: collisions by impulses with a coefficient of
// restitution, resting contact and friction by sequential impulses, and
// collision time by backtracking.
//
// One step of length dt, in sub-steps that end at the moments of impact:
//  1. detect contacts at the current poses (speculative within `slop`);
//  2. collision phase (Guendelman, Bridson and Fedkiw 2003, "Nonconvex rigid
//     bodies with stacking"): on the velocities before this step's forces,
//     every contact approaching faster than collision_threshold gets
//       j = -(1+e) v_rel / (1/ma + 1/mb + n.(Ia^-1 (ra x n)) x ra + n.(Ib^-1 (rb x n)) x rb)
//     (Hahn 1988; Mirtich 1996), with Coulomb friction clamped to mu j, in
//     passes until none approaches (this propagates through a Newton's cradle);
//  3. forces: P += F h, L += tau h;
//  4. contact phase: sequential impulses with accumulated clamping (Catto
//     2005) so that no contact approaches (v_rel >= 0, no bounce) and
//     friction stays in the Coulomb disk |lambda_t| <= mu lambda_n,
//     warm-started from the previous step's contact forces matched by body
//     pair and feature id (without it a stack of boxes never converges in
//     the iteration cap and its friction creeps sideways);
//     in components whose mass ratio is direct_mass_ratio or more the
//     normal rows are then solved directly (subspace_solve.h: Gauss-Seidel
//     converges at about 1 - m_light / m_heavy per sweep there);
//  4b. joints: the equality-constraint velocity solve (contact/joints/
//     joint_solver.h) after the forces and contact impulses;
//  5. positions: bodies without contact impulses fly ballistically,
//     x += v0 h + F/(2m) h^2 (exact under constant force, so bounce heights
//     carry no O(dt) bias); the others x += v h;
//  6. time of impact: if a pair that was apart now overlaps deeper than
//     slop, go back to the start of the sub-step, find the first time t_c
//     its depth reaches zero by bisection or regula falsi, move everything
//     to t_c and start a new sub-step there (at most max_substeps); a
//     sub-step after an impact checks after impact_sweeps sweeps and, found
//     free of impacts, is swept again in full (docs/methods/impulse.md,
//     "Sweeps before the impact check").
// After the step the joints' drift is projected away (post-stabilisation,
// joint_solver.h). Penetration left over is removed at the next step's start by a split
// impulse (pseudo-velocities that move positions, never velocities), so the
// correction adds no kinetic energy.
//
// Threads (impulse_stages.cpp): the passes of steps 2 and 4 and of the split
// impulse run over the rows' body pairs colour by colour (block_colours.h:
// two pairs of one colour share no moving body), each pass of one
// ParallelRunner::Stages call a list of stages (colour_stages.h) with a
// serial stage after it that decides whether to go on; the joint solves are
// serial stages too, and the contacts on jointed bodies keep their order
// after the colours, as lcp's rows on jointed bodies do (row_schedule.h).
// One thread runs the same stages in the same order, so the state does not
// depend on the thread count (docs/architecture.md, "Threads"). Within a
// pass the pairs go colour by colour rather than in contact order once
// there are 256 of them (impulse_stages.cpp, kMinColouredGroups; fewer keep
// the contact order): a Newton's cradle, whose pairs alternate two
// colours, then carries an impact down n balls in about n / 2 collision
// passes instead of one, and a tall aligned stack can lean
// (docs/physics.md, "impulse on threads").
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/block_colours.h"
#include "service/contact/contact_method.h"
#include "service/contact/contact_row.h"
#include "service/contact/impulse/impulse_params.h"
#include "service/contact/normal_block.h"
#include "service/contact/joints/joint_block.h"
#include "service/contact/solver_body.h"
#include "service/contact/subspace_solve.h"
#include "service/contact/warm_start_cache.h"

namespace contactsim {

class ColourStages;

class ImpulseMethod : public ContactMethod {
 public:
  const char* Name() const override { return "impulse"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kImpulse; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override { return ImpulseParamTable().ToMap(params_); }
  std::vector<ParamDoc> ParamDocs() const override { return ImpulseParamTable().Docs(); }
  // In joint_substeps sub-steps when the world's joints join very unequal
  // masses (joint_substeps.h), else one StepOnce.
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  void ResetCaches() override { warm_.Clear(); }
  // the warm-start forces, bit for bit, for snapshots
  std::string SaveState() const override;
  Status LoadState(const std::string& bytes) override;
  const ImpulseParams& params() const { return params_; }

 private:
  // One step over world.dt, without World::FinishStep.
  StepStats StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts);
  void CorrectPositions(World& world, const ContactSet& contacts);
  int CollisionPhase(std::vector<ContactRow>& rows);
  // Up to `sweeps` sweeps, *converged when they met velocity_tolerance;
  // the forces to keep for the warm start are left in warm_forces_ (stored
  // once the sub-step's impact check has kept them).
  int ContactPhase(const World& world, const ContactSet& contacts, double h, int sweeps,
                   std::vector<ContactRow>& rows, bool* converged);
  // Each contact's warm-start impulses from the cache (or zero), not yet applied.
  void LoadWarmStart(const ContactSet& contacts, double h, std::vector<ContactRow>& rows);
  // The colouring's view of the bodies (solver_): static and kinematic ones
  // fixed, jointed ones serial, the rest coloured.
  void SetColourRoles(const World& world);
  // Reorders `groups` (runs of rows on one body pair) colour by colour, or
  // keeps them in order as the overflow when they are few.
  BlockColours ColourGroups(const std::vector<ContactRow>& rows, std::vector<NormalBlock>* groups) const;
  // One collision pass over a pair's rows; true when one of them approached.
  bool CollideGroup(const NormalBlock& g, std::vector<ContactRow>& rows);
  // CollideGroup on groups_[g] as the phase's check number `order`, or
  // false at once when no impulse reached its bodies since its last check
  // found nothing approaching.
  bool CollideChanged(int g, int64_t order, std::vector<ContactRow>& rows);
  // The contact phase's warm start (the rows' lambdas onto solver_), the
  // joints' rows at the warm-started velocities and the sweeps, on the
  // runner; returns the sweeps done, whether they converged and whether
  // the joints were solved between them.
  int SweepContacts(const World& world, double h, int max_sweeps, std::vector<ContactRow>& rows, bool* converged,
                    bool* interleave);
  // The split impulse's sweeps over split_rows_ toward `target`, on the runner.
  void SweepPositions(const std::vector<double>& target);
  // Up to `passes` passes, each appended to a stage list by add_pass, after
  // prologue's stages (when given), in Stages calls of 1, 2, 4, ... passes
  // until `done`: the passes after `done` would only make the threads meet
  // at stages that do nothing (a settled pyramid's collision phase is done
  // after the first of its 20 passes). The same passes in the same order
  // as one call.
  void RunPasses(int passes, const bool& done, const std::function<void(ColourStages&)>& prologue,
                 const std::function<void(ColourStages&)>& add_pass);
  // A contact row's angular terms for d = n, t1, t2, found once a contact
  // phase (as Bullet's angularComponentA/B and relpos1CrossNormal): its
  // bodies' I^-1 (r x d), and r x d itself, with which the velocity along d
  // is d.(v_B - v_A) + (r_B x d).w_B - (r_A x d).w_A (d.(w x r) = w.(r x d))
  // and an impulse j d adds j (r x d) to L, so the sweeps take no cross
  // products. The friction rows' r is where the friction acts (fa, fb).
  struct AngularResponse {
    Vec3 a_n, a_t1, a_t2, b_n, b_t1, b_t2;    // I^-1 (r x d)
    Vec3 ra_n, fa_t1, fa_t2, rb_n, fb_t1, fb_t2;  // r x d
  };
  // responses_ for `rows` at solver_'s inertias: once a sub-step, for both
  // phases (the forces between them leave the orientations as they are).
  void FindResponses(const std::vector<ContactRow>& rows);
  // The relative velocity of B against A along d, from r x d.
  static double RowVelocity(const SolverBody& A, const SolverBody& B, const Vec3& d, const Vec3& ra_d,
                            const Vec3& rb_d) {
    return d.dot(B.v - A.v) + rb_d.dot(B.w) - ra_d.dot(A.w);
  }
  double NormalVelocity(const ContactRow& row, const AngularResponse& r) const {
    return RowVelocity(solver_[row.a], solver_[row.b], row.n, r.ra_n, r.rb_n);
  }
  // +J on B and -J on A, whose angular velocities change by +dwb and -dwa
  // and angular momenta by +dlb and -dla (the sums of
  // SolverBody::ApplyImpulse, with r x J from AngularResponse); inlined by
  // force: GCC called it out of line from the friction rows, which paid
  // its six vector arguments through memory
  [[gnu::always_inline]] void Push(const ContactRow& row, const Vec3& J, const Vec3& dwa, const Vec3& dwb, const Vec3& dla,
            const Vec3& dlb) {
    SolverBody& A = solver_[row.a];
    SolverBody& B = solver_[row.b];
    if (B.inv_mass != 0.0) {
      B.v += B.inv_mass * J;
      B.w += dwb;
      B.dP += J;
      B.dL += dlb;
    }
    if (A.inv_mass != 0.0) {
      A.v -= A.inv_mass * J;
      A.w -= dwa;
      A.dP -= J;
      A.dL -= dla;
    }
  }
  // dn along the row's normal
  void PushNormal(const ContactRow& row, const AngularResponse& r, double dn) {
    Push(row, dn * row.n, dn * r.a_n, dn * r.b_n, dn * r.ra_n, dn * r.rb_n);
  }
  // One Gauss-Seidel update of a block of the contact phase: each point's
  // friction, then the block's normal rows (normal_block.h); returns the
  // largest change of a relative velocity (m/s).
  double SweepBlock(const NormalBlock& m, std::vector<ContactRow>& rows);
  void BuildNormalBlocks(const std::vector<ContactRow>& rows);
  // The block's normal increments -step, rigid (v_n -> 0); false when a
  // point's impulse would go below 0 (the points are then swept one by one).
  bool NormalBlockStep(const NormalBlock& m, const std::vector<ContactRow>& rows, Eigen::Vector4d* step) const;
  // The direct solve of the normal rows (target velocity `target[k]`, or 0
  // and the friction rows without targets) in components with a large mass
  // ratio, after the sweeps; with `joints`, also in the components of the
  // jointed bodies the rows touch, with the joint rows (jointed_contacts.h).
  void SolveMassRatios(std::vector<ContactRow>& rows, const std::vector<double>* target, bool joints = false);
  // A pair whose deepest point went past `depth` in the sub-step: 0 for a
  // pair that was apart, the depth it started at plus half the margin for
  // a pair that was touching (another of its features struck).
  struct Impact {
    int a = 0, b = 0;
    double depth = 0.0;  // m
  };
  // The pairs that overlap a margin deeper now than at the sub-step's
  // start (`bodies` moved on from there by `h`): pairs that were apart,
  // and touching pairs whose motion could close a margin in h.
  std::vector<Impact> FindImpacts(const std::vector<RigidBody>& bodies, const ContactSet& contacts,
                                  CollisionDetector& detector, double h);
  // touching_ from the contacts at the sub-step's start.
  void FindTouching(const ContactSet& contacts);
  // Steps 3-5 from the world as the collision phase left it: forces, the
  // contact phase (up to `sweeps`) on rows_, positions; the sweeps done.
  int SweepAndMove(World& world, const ContactSet& contacts, double h, int sweeps, bool* converged);
  // The first impact's time in (0, h] from start_bodies_ for the pairs
  // that overlap at `bodies` (step 6), or h when none does.
  double ImpactTime(const std::vector<RigidBody>& bodies, const ContactSet& contacts, CollisionDetector& detector,
                    double h, int* iterations);
  // Moves the bodies over h (step 5), split over the runner's threads.
  void MoveBodies(double h, World& world);
  // *to = from, split over the runner's threads (the sub-step's start state).
  void CopyBodies(const std::vector<RigidBody>& from, std::vector<RigidBody>* to) const;
  // First time in (0, h] at which an impact's pair reaches its depth, or h.
  double FindImpactTime(const std::vector<RigidBody>& start, const std::vector<Impact>& impacts, double h,
                        int* iterations);

  ImpulseParams params_;
  ParallelRunner* runner_ = nullptr;  // the detector's, for the step
  std::vector<SolverBody> solver_;
  std::vector<ColourRole> roles_;           // per solver body
  std::vector<NormalBlock> groups_;         // the collision phase's pairs, colour by colour
  std::vector<double> target_, impulse_;    // per row, the collision phase's
  std::vector<char> group_hit_;             // per group, in the last collision pass
  std::vector<int64_t> checked_at_;         // per group: the number of its last check, or -1
  std::vector<int64_t> pushed_at_;          // per solver body: the last check that pushed it, or -1
  BlockColours colours_;                    // of blocks_ (or groups_), for the passes
  std::vector<double> block_worst_;         // per block, its largest change in the last pass
  std::vector<ParallelRunner::Stage> stages_;
  std::vector<ContactSet> impact_scratch_;  // per worker
  std::vector<double> impact_depth_;        // per candidate pair: the impact's depth, or NaN
  std::vector<double> impact_deepest_;      // per worker: the impact search's deepest at one time
  struct Touching {
    BodyPair pair;  // body indices, lower first
    double depth;   // m, of the pair's deepest contact
    Vec3 normal;    // unit, world, that contact's normal from pair.first to pair.second
  };
  std::vector<Touching> touching_;  // the pairs in contact at the sub-step's start, by pair
  std::vector<Touching> touching_points_;  // FindTouching's: per contact, by pair
  std::vector<int> touching_offsets_;      // FindTouching's: the pairs before each run of kRowGrain points
  JointVelocityBlock joints_;  // the step's joint rows, solved between the sweeps
  std::vector<Vec3> friction_points_;  // with patch_torsion (patch_torsion.h)
  std::vector<AngularResponse> responses_;  // per contact row, reused between steps
  std::vector<ContactRow> rows_;
  // the split impulse's rows, apart from rows_ so that neither shrinks and
  // grows again each step (a row is dear to construct)
  std::vector<ContactRow> split_rows_;
  std::vector<ContactRow> collision_rows_;  // rows_ after the collision phase, for a sub-step swept again
  std::vector<RigidBody> start_bodies_;     // the sub-step's start state (kept: a body is dear to construct)
  std::vector<int> row_of_;                 // per contact: its split impulse row, or -1
  std::vector<NormalBlock> blocks_;         // the rows by body pair, up to four
  std::vector<ConstraintRow> normal_rows_;  // the rows for the direct solve
  std::vector<char> jointed_contacts_;      // per body: jointed and touched (jointed_contacts.h)
  SubspaceSolver subspace_;
  // Contact-phase force (N: normal, and tangent along the contact frame's
  // PerpendicularBasis) of each contact point of the last sub-step, by pair
  // and feature id or else by place (warm_start_cache.h). Forces, not
  // impulses, so that sub-steps of another length reuse them.
  WarmStartCache warm_;
  std::vector<std::array<double, 3>> warm_forces_;  // per contact, to store
};

}  // namespace contactsim
