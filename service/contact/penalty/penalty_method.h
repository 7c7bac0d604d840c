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
// Stiffness: with contact_time T > 0 (the default, linear law) a pair's
// kp = m_s pi^2 / T^2, m_s the heaviest body of its contact island, and
// kt = kp (penalty_stiffness.h); with T = 0 the fixed kp and
// friction_stiffness.
//
// One step of dt:
//  explicit (default; penalty_explicit.h): one detection with a speculative
//     margin (what the step can close), one row per point, then as many
//     sub-steps of symplectic Euler as resolve a rebounding pair's spring
//     (max_omega_h) and keep the stiffest mode stable (power iteration),
//     each point's depth carried with its bodies' motion; bodies that no
//     contact pushes fly ballistically; with impacts = sequential, a pair
//     closing within a sub-step faster than impact_threshold first takes
//     its component's impacts one at a time (penalty_impacts.h);
//  implicit: in `substeps` sub-steps of h = dt / substeps, each a detection
//     with depth > -margin, rows (penalty_row.h), the linearly implicit
//     momentum step (penalty_implicit.h), then positions with the
//     theta-weighted velocity x += h ((1 - theta) v0 + theta v1).
//  Friction anchors advance by the slip, s += h v_t; anchors of points that
//  carried no force are dropped.
//  Joints: the equality-constraint velocity solve (contact/joints/
//  joint_solver.h) on the momenta after each momentum update, before the
//  positions move; after the positions, their drift is projected away.
// Contact::normal_value and tangent_value are forces (N): the normal force
// on B and the friction force on B (world) of the last sub-step, the normal
// one plus the impulse of an impact the stage took in the step divided by
// the step (its mean force: the impact may end before the pair touches, and
// is reported all the same); depth is
// the point's depth at the step's end.
// StepStats: iterations = active-set passes of the implicit solve (0 when
// explicit), residual = its largest complementarity violation left (N),
// substeps = sub-steps taken, max_penetration = deepest point seen (at any
// sub-step when explicit).
#pragma once

#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/penalty/penalty_friction.h"
#include "service/contact/penalty/penalty_impacts.h"
#include "service/contact/penalty/penalty_params.h"
#include "service/contact/penalty/penalty_preload.h"
#include "service/contact/penalty/penalty_row.h"

namespace contactsim {

class PenaltyMethod : public ContactMethod {
 public:
  const char* Name() const override { return "penalty"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kForce; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override;
  std::vector<ParamDoc> ParamDocs() const override;
  // In joint_substeps sub-steps when the world's joints join very unequal
  // masses (joint_substeps.h), else one StepOnce.
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  void ResetCaches() override { anchors_.Clear(); }
  // the friction anchors (FrictionAnchors::Save)
  std::string SaveState() const override;
  Status LoadState(const std::string& bytes) override;
  const PenaltyParams& params() const { return params_; }
  const FrictionAnchors& anchors() const { return anchors_; }

 private:
  // One step over world.dt, without World::FinishStep.
  StepStats StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts);
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
  PenaltyImpacts impacts_;  // the explicit step's impact stage (penalty_impacts.h)
  PenaltyPreload preload_;  // the explicit step's load-aware start (penalty_preload.h)
};

}  // namespace contactsim
