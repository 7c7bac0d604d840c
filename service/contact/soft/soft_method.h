// The soft-step method: sequential impulses on soft contact constraints in
// sub-steps with relaxation and restitution after the solve, the solver of
// Box2D v3 and Box3D (Catto, Solver2D "Soft Step", 2024).
//
// One step of dt:
//  1. detect once, speculatively (detect_ahead.h): each pair's contacts
//     within `margin` plus how far it can close in dt;
//  2. bodies without a contact fly the whole step ballistically
//     (AdvanceBallistic, exact under constant force); the others take
//     `substeps` sub-steps of h = dt / substeps, each
//       a. v += h F / m, w += h I^-1 tau;
//       b. warm start: apply the accumulated impulses;
//       c. solve: every contact point once, normal then Coulomb-disk friction,
//          the pairs from the highest down (sweep_order.h),
//          a penetrating point as a soft spring of contact_hertz and
//          damping_ratio (softness.h: the stiffness scales with the effective
//          mass, so mass ratios do not make it softer or stiffer) that pushes
//          out no faster than max_push_velocity; a separated point
//          speculatively (it may close its gap within h but not pass it);
//       d. positions from the velocities; each point's separation follows
//          from its anchors (soft_contact.h), with no narrowphase;
//       e. relax: `relax_iterations` passes with rigid, unbiased rows, which
//          take back the velocity the spring gave, so pushing out adds no
//          kinetic energy;
//     where a heavy body rests on a light one (direct_mass_ratio), the
//     springs take their stiffness from the heavy body and each solve and
//     relax pass ends with a direct solve of those contacts
//     (soft_ratio_solve.h);
//  3. restitution: in components where a point that pushed met faster
//     than the threshold (max(restitution_threshold, 2 |g| dt)), the
//     points that pushed leave with the normal velocities of the impacts
//     taken one at a time (soft_restitution.h), -e v_impact for a lone pair;
//  4. the contacts are kept with their impulses, pair by pair, for the next
//     step's warm start (persistent_contacts.h).
// Small sub-steps with one iteration each converge better than many
// iterations of one step (Macklin et al. 2019, "Small steps in physics
// simulation"), so stacks stand at four passes a step.
//
// Contacts report the impulse of the whole step (ValueKind kImpulse): the sum
// of each sub-step's accumulated impulse and the restitution impulse.
// Joints: the exact velocity solve of joint_solver.h after each contact
// pass, the positions projected onto the joints after the step
// (soft_joints.h); a body held only by a joint moves sub-step by sub-step.
// The points on jointed bodies and their joints' rows are solved together
// after the last contact pass of each stage (soft_jointed_solve.h).
#pragma once

#include <array>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/block_colours.h"
#include "service/contact/contact_method.h"
#include "service/contact/persistent_contacts.h"
#include "service/contact/sequential_impacts.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/soft/soft_joints.h"
#include "service/contact/soft/soft_jointed_solve.h"
#include "service/contact/soft/soft_manifold.h"
#include "service/contact/soft/soft_params.h"
#include "service/contact/soft/soft_point_order.h"
#include "service/contact/soft/soft_ratio_solve.h"
#include "service/contact/soft/wide/soft_wide_solver.h"

namespace contactsim {

class SoftMethod : public ContactMethod {
 public:
  const char* Name() const override { return "soft"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kImpulse; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override { return SoftParamTable().ToMap(params_); }
  std::vector<ParamDoc> ParamDocs() const override { return SoftParamTable().Docs(); }
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  void ResetCaches() override { warm_start_.Clear(); }
  std::string SaveState() const override { return warm_start_.Save(); }
  Status LoadState(const std::string& bytes) override;
  const SoftParams& params() const { return params_; }

 private:
  void Prepare(World& world, ParallelRunner& runner);
  // Colours the manifolds (after the ratio solve has chosen its points).
  void ColourManifolds();
  // Steps 2 to 3 above as the stages of one ParallelRunner::Stages call
  // (soft_stages.cpp).
  void RunSubsteps(World& world, ParallelRunner& runner);
  // The contacts with their step's impulses and end depths, on the threads;
  // without a request for the report (contact_method.h), the contacts as
  // detected, handed over without a copy.
  StepStats Report(ParallelRunner& runner, ContactSet* contacts);
  // where the points' friction acts with patch_torsion (patch_torsion.h);
  // null: at the points
  const std::vector<Vec3>* FrictionPoints() const;
  // the contact springs of a sub-step
  SoftSprings Springs(const World& world) const;
  // Restitution applies to approaches faster than this (m/s).
  double RestitutionThreshold(const World& world) const;

  SoftParams params_;
  ContactSet contacts_;
  std::vector<char> in_contact_;
  std::vector<SoftBody> bodies_;
  std::vector<Vec3> friction_points_;  // with patch_torsion (patch_torsion.h)
  std::vector<SoftPoint> points_;
  SoftPointOrder point_order_;  // where each contact's point is
  std::vector<SoftManifold> manifolds_;  // colour by colour (block_colours.h)
  std::vector<ColourRole> roles_;  // per body
  BlockColours colours_;
  std::vector<ParallelRunner::Stage> stages_;
  SoftPointsOfBodies points_of_bodies_;
  std::vector<int> body_order_;   // the body stages' order (soft_stages.cpp)
  std::vector<char> body_seen_;   // its scratch
  SoftJoints joints_;
  SoftRatioSolve ratio_solve_;
  SoftJointedSolve jointed_solve_;
  SoftWideSolver wide_;  // precision=float
  // this step's points and manifolds wait for the float path's prepare
  // kernel (no rows, no K^-1 yet)
  bool wide_prepare_ = false;
  SequentialImpacts impacts_;
  PersistentContacts warm_start_;
};

}  // namespace contactsim
