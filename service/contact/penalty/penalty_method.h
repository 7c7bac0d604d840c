// The penalty method: a spring-damper at every contact point (Parent,
// "Computer Animation: Algorithms and Techniques", ch. 7.4), applied to both
// bodies at the point, so off-centre contacts make torques:
//   lambda = max(0, kp d - kd vn) / nc        (model = linear)
//   lambda = max(0, kp d^n (1 - 1.5 alpha vn)) / nc   (model = hunt_crossley)
// with d the depth, vn the separating normal velocity and nc the number of
// contact points of the pair (penalty_force.h, penalty_row.h). kd (or alpha) comes
// from a restitution coefficient unless given (penalty_force.h: the exact
// no-tension relation of the linear dashpot). Friction is a tangential
// spring from an anchor with a Coulomb limit (Yamane and Nakamura 2006,
// penalty_friction.h).
//
// One step of dt, in `substeps` sub-steps of h = dt / substeps, each:
//  1. detect contacts with depth > -margin, build one row per point
//     (penalty_row.h);
//  2. explicit: the forces at the sub-step's start are added to each body's
//     force and torque, then IntegrateMomenta and IntegratePositions
//     (semi-implicit Euler, stable while sqrt(kp / m) h < 2). Each dashpot
//     (normal c, tangential ct) acts as c / (1 + h c K), K the point's
//     inverse effective mass along it: the force a lone dashpot integrated
//     implicitly would give, so it never reverses the point's velocity in
//     one step. Why: a rocking box sees the normal and the tangential
//     dashpots of its corners against its small moment of inertia, and
//     with plain dashpots (critically damped for the translation) its
//     rocking diverged at kp = 1e5 N/m, kt = 1e4 N/m for a 0.2 m box. For
//     h c K << 1 (resolved bounces) the factor is 1;
//     implicit: the linearly implicit momentum step (penalty_implicit.h),
//     then positions with the theta-weighted velocity
//     x += h ((1 - theta) v0 + theta v1) (same rotation update);
//  3. the anchors advance by the slip: s += h v_t; anchors of points that
//     carried no force are dropped.
//  Joints: the equality-constraint velocity solve (contact/joints/
//  joint_solver.h) on the momenta after step 2's momentum update, before the
//  positions move; after the positions, their drift is projected away.
// Contact::normal_value and tangent_value are forces (N): the normal force
// on B and the friction force on B (world) of the last sub-step.
// StepStats: iterations = active-set passes of the implicit solve (0 when
// explicit), residual = its largest complementarity violation left (N),
// substeps = sub-steps taken, max_penetration = deepest point seen.
#pragma once

#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/penalty/penalty_friction.h"
#include "service/contact/penalty/penalty_params.h"
#include "service/contact/penalty/penalty_row.h"

namespace contactsim {

class PenaltyMethod : public ContactMethod {
 public:
  const char* Name() const override { return "penalty"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kForce; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override;
  std::vector<ParamDoc> ParamDocs() const override;
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  void ResetCaches() override { anchors_.Clear(); }
  // the friction anchors (FrictionAnchors::Save)
  std::string SaveState() const override;
  Status LoadState(const std::string& bytes) override;
  const PenaltyParams& params() const { return params_; }
  const FrictionAnchors& anchors() const { return anchors_; }

 private:
  // one detection, then the explicit sub-steps (penalty_explicit.h)
  void ExplicitWorldStep(World& world, CollisionDetector& detector, StepStats* stats);
  // `substeps` detections, each with the linearly implicit step (penalty_implicit.h)
  void ImplicitWorldStep(World& world, CollisionDetector& detector, StepStats* stats);
  void ImplicitSubstep(World& world, double h, StepStats* stats);
  // advances the anchors of the force-carrying points by the slip
  void KeepAnchors(const World& world, const ContactSet& contacts, double h);

  PenaltyParams params_;
  FrictionAnchors anchors_;
  ContactSet contacts_;
  std::vector<PenaltyRow> rows_;
};

}  // namespace contactsim
