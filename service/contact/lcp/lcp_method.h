// The lcp contact method: contacts (and joints) as one complementarity
// problem per step, velocity-level time stepping after Stewart and Trinkle
// (IJNME 1996) and Anitescu and Potra (Nonlinear Dynamics 1997).
//
// One step of length h:
//  1. detect contacts at the current poses (speculative within `slop`);
//  2. colliding contacts are traced back to their moment of impact under
//     the step's constant forces (PredictImpact, lcp_contact_rows.h): the
//     normal row gets the exact end velocity after the bounce, and the
//     position the step would miss is added by the split impulse below
//     (under either drift rule);
//     drift = split (default): remove erp (depth - slop) of each
//     penetration by a split impulse, pseudo-velocities solved by PGS on the
//     normal rows and applied to positions only (Catto 2005; as the impulse
//     method does), so the correction adds no kinetic energy. drift =
//     baumgarte instead adds erp (depth - slop) / h to the normal rows'
//     target velocity, which can add energy (a resting stack jitters);
//  3. v* = v + h M^-1 f_ext (IntegrateMomenta);
//  4. rows: per contact a normal row with Newton restitution above
//     restitution_threshold and two friction rows (lcp_contact_rows.h);
//     with impacts = sequential the normal rows of contacts that meet in
//     components with restitution target the velocities of their impacts
//     taken one at a time (lcp_impacts.h);
//     then the joints' rows (BuildJointVelocityRows, joint_solver.h: the
//     same Jacobians and velocity products as under impulse and penalty),
//     bilateral (lo = -inf, hi = +inf) except hinge limits, so that joints
//     and contacts are ONE problem: a pendulum resting on a box gets its
//     rod tension and the contact force from the same solve;
//  5. solve for the impulses: solver = pgs (pgs.h: joint rows are unclamped
//     rows of the same sweeps; contact rows warm-started from last step's
//     impulses by feature id, joint rows by joint id; then, in components
//     with a mass ratio of direct_mass_ratio or more, a direct solve of the
//     normal and joint rows, subspace_solve.h) or lemke
//     (lemke_rows.h, the exact mixed LCP, joint rows its free variables; if
//     it fails or has more than max_lemke_rows rows the step falls back to
//     PGS, warm-started as solver = pgs is, and lemke_fallbacks() counts it);
//  6. positions: bodies that received no impulse fly ballistically,
//     x += v0 h + F/(2m) h^2 (exact under gravity, as in the impulse method);
//     the others x += v h; orientations by IntegratePositions;
//  7. joint drift: post-stabilisation (ProjectJointPositions, Cline and Pai
//     2003), as the impulse and penalty methods do: the velocity rows keep
//     C constant only to O(h^2) per step, the projection puts the positions
//     back on C = 0 without touching the velocities.
//
// StepStats: iterations = PGS sweeps or Lemke pivots; residual = the
// solver's residual (pgs: m/s, last sweep's largest row-velocity change);
// contacts; max_penetration. last_report() adds lemke's complementarity
// error (pgs's solves skip that measure: PgsOptions::measure_complementarity).
// Contact values are impulses (N s).
#pragma once

#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/joints/joint_rows.h"
#include "service/contact/lcp/lcp_contact_rows.h"
#include "service/contact/lcp/lcp_impacts.h"
#include "service/contact/lcp/lcp_params.h"
#include "service/contact/lcp/pgs.h"
#include "service/contact/warm_start_cache.h"
#include "service/contact/subspace_solve.h"

namespace contactsim {

class LcpMethod : public ContactMethod {
 public:
  const char* Name() const override { return "lcp"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kImpulse; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override { return LcpParamTable().ToMap(params_); }
  std::vector<ParamDoc> ParamDocs() const override { return LcpParamTable().Docs(); }
  // In joint_substeps sub-steps when the world's joints join very unequal
  // masses (joint_substeps.h), else one StepOnce.
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  void ResetCaches() override { warm_start_.Clear(); }
  // the warm-start impulses, bit for bit, for snapshots
  std::string SaveState() const override { return warm_start_.Save(); }
  Status LoadState(const std::string& bytes) override;

  const LcpParams& params() const { return params_; }
  const SolveReport& last_report() const { return report_; }
  int lemke_fallbacks() const { return lemke_fallbacks_; }
  const WarmStartCache& warm_start() const { return warm_start_; }

 private:
  // One step over world.dt, without World::FinishStep.
  StepStats StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts);
  // Steps 2 and 4 above: impacts, the split impulse and the contact rows.
  // The per-body and per-contact loops and the PGS sweeps (colour by
  // colour, pgs.h) run on the runner's threads, here and below.
  void BuildContactRows(World& world, ParallelRunner& runner);
  void CorrectPositions(World& world, const ContactSet& contacts, const std::vector<Impact>& impacts,
                        ParallelRunner& runner);
  // Step 6 and 7 above.
  void AdvancePositions(World& world, ParallelRunner& runner);
  void Solve(const World& world, std::vector<SolverBody>& bodies, ParallelRunner& runner);
  // Solve on bodies_, again without the joint rows' velocity products where
  // they made it add kinetic energy (lcp_method.cpp).
  void SolveWithinEnergy(const World& world, size_t first_joint_row, ParallelRunner& runner);
  // warm_start_ from the rows, less the impacts' impulses
  void StoreWarmStart(ParallelRunner& runner);
  // where the contacts' friction acts with patch_torsion, else null (the contact points)
  const std::vector<Vec3>* FrictionPoints() const {
    return friction_points_.empty() ? nullptr : &friction_points_;
  }

  LcpParams params_;
  ContactSet contacts_;
  std::vector<Vec3> friction_points_;  // patch_torsion.h
  std::vector<SolverBody> before_, free_, bodies_;
  std::vector<Impact> impacts_;
  SequentialImpacts sequence_;           // impacts = sequential (lcp_impacts.h)
  std::vector<double> impact_impulses_;  // per contact, N s, the impacts' warm start (-1: none)
  std::vector<ConstraintRow> rows_, split_rows_, joint_rows_, lemke_rows_;
  // the solve's start, kept while SolveWithinEnergy checks its energy
  std::vector<SolverBody> energy_bodies_;
  std::vector<ConstraintRow> energy_rows_;
  std::vector<JointBlock> joint_blocks_;
  PgsSolver pgs_, split_pgs_;
  // each contact pair's normal rows (3 k for contact k), solved as blocks by pgs_
  std::vector<NormalBlock> pairs_;
  std::vector<PgsNormalBlock> normal_blocks_;
  SubspaceSolver subspace_;
  std::vector<char> jointed_contacts_;  // per body: jointed and touched (jointed_contacts.h)
  WarmStartCache warm_start_;
  SolveReport report_;
  int lemke_fallbacks_ = 0;
};

}  // namespace contactsim
