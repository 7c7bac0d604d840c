// The xpbd method: rigid bodies by extended position based dynamics
// (Mueller, Macklin, Chentanez, Jeschke and Kim 2020, "Detailed rigid body
// simulation with extended position based dynamics", SCA, Algorithm 2; the
// rigid-body constraints of Deul, Charrier and Bender 2014).
//
// One step of dt (the small-steps view: Macklin et al. 2019, "Small steps in
// physics simulation", many sub-steps of one iteration each):
//  1. detect once, speculatively (detect_ahead.h): each pair's contacts
//     within `margin` plus how far it can close in dt; each contact is kept
//     for the step by its anchors in the bodies' frames (xpbd_contact.h), so
//     the sub-steps bring its separation up to date without a narrowphase;
//  2. bodies without a contact or joint fly the whole step ballistically
//     (AdvanceBallistic, exact under constant force, as under every other
//     method); the others take `substeps` sub-steps of h = dt / substeps,
//     or more where a contact joins bodies of mass ratio r: one sweep a
//     sub-step leaves the heavy one about r g h^2 deep, so h is chosen to
//     keep that within kMassRatioOverlap (SubstepsFor):
//     a. predict: v += h F / m, w += h I^-1 tau; where joints have
//        damping, friction or actuator drives, their velocity rows
//        (joints/joint_rows.h, with the joints' geometry) at the sub-step
//        h on those velocities, so that the positions move by what the
//        implicit damper, the joint's friction and the drive leave (the
//        actuator model's q' = q + h v', joint_actuator.h; a velocity row
//        rather than a compliant positional constraint, so that velocity
//        control and the exact effort clamp on the impulse come alike);
//        then x, q from them (soft_bodies.h: L held across the turn);
//     b. solve positions, `iterations` times: joints (xpbd_joints.h, with
//        joint_compliance), then contacts (non-penetration, static
//        friction; xpbd_contact.h), the pairs from the highest down
//        (sweep_order.h), with compliance alpha (alpha~ = alpha /
//        h^2); rigid joints (joint_compliance 0) are then moved onto
//        C = 0 by one Newton step of all of them together
//        (ProjectJointPositions, joints/joint_solver.h, whose tree solve
//        takes O(n) for n joints without loops), which the sweeps approach
//        only slowly: a sweep shrinks the error of a chain of n joints by
//        about 1 - pi^2 / n^2 and across a mass ratio by about
//        1 - m_light / m_heavy, and one sweep a sub-step left a swinging
//        30-link chain open by 3.8 mm and gaining energy (docs/physics.md,
//        "Long chains and resting convex hulls"); the normal rows of
//        contact components of mass ratio direct_mass_ratio or more are
//        solved together (xpbd_ratio_solve.h); a contact on a body held
//        by rigid joints moves the body's jointed component as the joints
//        let it, through their constrained mobility at the sub-step's
//        predicted poses (xpbd_articulation.h), here and in d;
//     c. velocities from the poses (Algorithm 2): v += (x - x~) / h and
//        w += 2 vec(q q~^-1) / h, x~ and q~ the predicted pose;
//     d. velocity pass: restitution and dynamic friction; in components
//        with restitution the bounce is that of the impacts taken one at a
//        time (xpbd_restitution.h).
// Small sub-steps rather than many iterations is the paper's point: the
// error of one Gauss-Seidel sweep shrinks with h^2, so stacks stay stiff.
//
// Contacts report forces (ValueKind kForce): the step's contacts, each with
// its average force on B over the step, the sum of lambda / h (positional
// impulses) and the velocity pass's impulses over the sub-steps, divided by
// dt; lambda / h^2 is a sub-step's contact force.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/sequential_impacts.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/xpbd/xpbd_contact.h"
#include "service/contact/xpbd/xpbd_jointed_friction.h"
#include "service/contact/xpbd/xpbd_joints.h"
#include "service/contact/xpbd/xpbd_patch_friction.h"
#include "service/contact/xpbd/xpbd_params.h"
#include "service/contact/xpbd/xpbd_ratio_solve.h"
#include "service/contact/xpbd/xpbd_velocity_pass.h"

namespace contactsim {

class XpbdMethod : public ContactMethod {
 public:
  const char* Name() const override { return "xpbd"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kForce; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override { return XpbdParamTable().ToMap(params_); }
  std::vector<ParamDoc> ParamDocs() const override { return XpbdParamTable().Docs(); }
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  const XpbdParams& params() const { return params_; }
  // the slips static friction carries into the next step (XpbdPatchSlip)
  // and the overlaps still allowed (AllowXpbdStartOverlaps)
  void ResetCaches() override {
    slips_.clear();
    allowed_.clear();
  }
  std::string SaveState() const override;
  Status LoadState(const std::string& bytes) override;

 private:
  // The deepest a heavy body may rest in a light one (m), which sets the
  // sub-steps where the step's contacts join bodies of very different mass:
  // 0.45 mm gives a 1:1000 pair 20 sub-steps of 1/240 s.
  static constexpr double kMassRatioOverlap = 0.45e-3;
  // `substeps`, or more where a heavy body rests on a light one.
  int SubstepsFor(const World& world) const;
  // `substeps` sub-steps of predict, solve positions, derive velocities,
  // velocity pass, as the stages of one ParallelRunner::Stages call
  // (xpbd_stages.cpp).
  void RunSubsteps(World& world, int substeps, bool project_joints, ParallelRunner& runner);
  // v += (x - x~) / h, w += 2 vec(q q~^-1) / h for bodies [begin, end).
  void DeriveVelocities(const World& world, double h, int begin, int end);
  // The step's contacts with their depth at the step's end and average force.
  void ReportContacts(const World& world, ContactSet* contacts_out, StepStats* stats) const;

  // The slips static friction left at the last step's end, by body pair
  // (ids, in the contact's order) and the patch's place among the pair's
  // patches: 0 for a plain pair's one patch, 1 + its points' smallest
  // feature id for a compound's child pairs (PatchKeys): XpbdPatchSlip.
  using PairKey = std::tuple<BodyId, BodyId, int64_t>;
  std::map<PairKey, XpbdPatchSlip> slips_;
  // patch k's PairKey
  std::vector<PairKey> PatchKeys(const World& world) const;
  void CarrySlips(const World& world);
  void KeepSlips(const World& world);

  // The overlap each body pair in contact at the last step's end was still
  // allowed (m; 0 for most), by ids in the contact's order. A pair not in
  // it is new (placed, or the world switched to xpbd), and its overlaps are
  // start overlaps; a pair's allowance only shrinks, so the overlaps its
  // sweeps leave under load are never allowed and pushed out as before.
  struct AllowedOverlap {
    BodyId a = 0, b = 0;
    double overlap = 0.0;  // m
    bool operator<(const AllowedOverlap& o) const { return a < o.a || (a == o.a && b < o.b); }
  };
  std::vector<AllowedOverlap> allowed_;  // sorted by (a, b), one entry a pair
  std::vector<AllowedOverlap> kept_;     // the next step's, being gathered
  void AllowStartOverlaps(const World& world, int substeps);
  void KeepAllowedOverlaps(const World& world);
  // sorts by pair, one entry a pair (the largest overlap)
  static void SortAllowed(std::vector<AllowedOverlap>* allowed);

  XpbdParams params_;
  ContactSet contacts_;                   // detected once per step
  std::vector<char> substepped_;
  std::vector<char> touching_;            // per body: it has a contact this step
  XpbdArticulation articulation_;         // the contacts' view of jointed bodies
  std::vector<int> jointed_blocks_;       // the blocks of jointed points
  XpbdJointedFriction jointed_friction_;  // their patches' static friction together
  std::vector<SoftBody> bodies_;
  std::vector<XpbdPoint> points_;         // in the blocks' order
  std::vector<XpbdPointFrame> frames_;    // parallel to points_
  std::vector<int> point_of_;             // contact k's place in points_
  std::vector<NormalBlock> blocks_;      // from the top down, then colour by colour
  BlockColours colours_;
  std::vector<XpbdPatch> patches_;        // parallel to blocks_
  std::vector<XpbdSubsetCache> subsets_;  // parallel to blocks_
  XpbdRatioSolve ratio_;                  // heavy-on-light components' direct solve
  std::vector<XpbdPose> predicted_;
  std::vector<XpbdJointLambda> joint_lambdas_;
  std::vector<ParallelRunner::Stage> stages_;
  SequentialImpacts impacts_;             // a sub-step's restitution rows (xpbd_restitution.h)
  std::vector<char> deferred_;            // per block: restitution left to impacts_
  std::vector<char> struck_;              // per body: its component took part in impacts_ this step
  std::vector<XpbdPassBlock> pass_blocks_;  // per block: its state over the velocity pass's sweeps
};

}  // namespace contactsim
