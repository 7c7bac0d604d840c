// The xpbd method: rigid bodies by extended position based dynamics
// (Mueller, Macklin, Chentanez, Jeschke and Kim 2020, "Detailed rigid body
// simulation with extended position based dynamics", SCA, Algorithm 2; the
// rigid-body constraints of Deul, Charrier and Bender 2014).
//
// One step of dt: find the candidate pairs once, those with a contact within
// a margin widened per pair by how far it can close in dt, so that every
// sub-step sees the pairs about to meet; then `substeps` sub-steps of
// h = dt / substeps, each
//  1. predict: P += F h, L += tau h, then x, q from the new velocities
//     (the integrator of service/physics, so free flight is the same as
//     under every other method), and collide the candidate pairs at the
//     predicted poses (the paper's sec. 3.5: broadphase once per step,
//     narrowphase per sub-step);
//  2. solve positions, `iterations` times: joints (xpbd_joints.h, with
//     joint_compliance), then contacts (non-penetration, static friction;
//     xpbd_contact.h) with compliance alpha (alpha~ = alpha / h^2); rigid
//     joints between bodies of mass ratio direct_mass_ratio or more are
//     then projected onto C = 0 by Newton's method (ProjectJointPositions,
//     joints/joint_solver.h), which the sweeps approach only at a rate of
//     about 1 - m_light / m_heavy;
//  3. velocities from the poses: bodies moved by the solve get
//     P += m dx / h and L += I dw with dw = 2 vec(dq) / h, dq the rotation the
//     solve added (a body the solve left alone keeps its momenta exactly);
//  4. velocity pass: dynamic friction and restitution (xpbd_contact.h).
// Small sub-steps rather than many iterations is the paper's point: the
// error of one Gauss-Seidel sweep shrinks with h^2, so stacks stay stiff.
//
// Contacts report forces (ValueKind kForce): the last sub-step's contacts,
// each with the step's average force on B of its feature pair, the sum of
// lambda / h (positional impulses) and the velocity pass's impulses over the
// sub-steps, divided by dt; lambda / h^2 is a sub-step's contact force.
#pragma once

#include <string>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/contact/contact_method.h"
#include "service/contact/xpbd/xpbd_contact.h"
#include "service/contact/xpbd/xpbd_joints.h"
#include "service/contact/xpbd/xpbd_params.h"

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

 private:
  // The body pairs of detected_ (sorted, unique): the sub-steps' narrowphase.
  void CandidatePairs();
  // contacts_ (and substep_contacts_) at the current poses of the candidates.
  void CollideCandidates(const World& world);
  // The last sub-step's contacts with the step's impulses of their features.
  void ReportContacts(const World& world, ContactSet* contacts_out, StepStats* stats);

  using ContactKey = std::tuple<int, int, uint32_t>;  // body a, body b, feature id
  struct KeyedImpulse {
    ContactKey key;
    Vec3 impulse;  // N s on B over one sub-step
  };
  static ContactKey KeyOf(const Contact& c);

  XpbdParams params_;
  Narrowphase narrowphase_;               // with its own separating-axis cache
  ContactSet detected_;                   // once per step, with each pair's reach
  std::vector<BodyPair> candidates_;
  ContactSet substep_contacts_;           // this sub-step's, parallel to contacts_
  std::vector<KeyedImpulse> impulses_;
  std::vector<XpbdContact> contacts_;
  std::vector<XpbdPose> start_, predicted_;
  std::vector<XpbdJointLambda> joint_lambdas_;
};

}  // namespace contactsim
