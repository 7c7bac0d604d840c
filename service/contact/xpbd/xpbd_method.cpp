#include "service/contact/xpbd/xpbd_method.h"

#include <algorithm>
#include <tuple>

#include "service/collision/narrowphase.h"
#include "service/contact/detect_ahead.h"
#include "service/contact/joints/joint_mass_ratio.h"
#include "service/contact/joints/joint_solver.h"
#include "service/physics/integrator.h"

namespace contactsim {

Status XpbdMethod::SetParams(const ParamMap& params) {
  return XpbdParamTable().Parse(Name(), params, params_, &params_);
}

void XpbdMethod::CandidatePairs() {
  // the pairs with a contact within margin + their closing distance over
  // the step: only they can touch before the next detection
  candidates_.clear();
  for (const Contact& c : detected_) {
    if (candidates_.empty() || candidates_.back() != BodyPair{c.a, c.b}) candidates_.push_back({c.a, c.b});
  }
  std::sort(candidates_.begin(), candidates_.end());
  candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());
}

void XpbdMethod::CollideCandidates(const World& world) {
  // contacts at the predicted poses of this sub-step (the paper's sec. 3.5:
  // broadphase once per step, narrowphase every sub-step), so that a
  // tumbling box is held by the corners it now presents, not those it
  // presented at the start of the step
  const auto& bodies = world.bodies();
  substep_contacts_.clear();
  for (const BodyPair& p : candidates_) {
    narrowphase_.Collide(bodies[p.first], p.first, bodies[p.second], p.second, params_.margin, &substep_contacts_);
  }
  contacts_.clear();
  for (const Contact& c : substep_contacts_) contacts_.push_back(MakeXpbdContact(c, world));
}

XpbdMethod::ContactKey XpbdMethod::KeyOf(const Contact& c) { return {c.a, c.b, c.feature_id}; }

void XpbdMethod::ReportContacts(const World& world, ContactSet* contacts_out, StepStats* stats) {
  // a contact of the last sub-step reports the impulses of every sub-step
  // in which its features touched (by feature id); a feature pair that
  // parted more than the margin before the last sub-step is not reported
  std::sort(impulses_.begin(), impulses_.end(),
            [](const KeyedImpulse& l, const KeyedImpulse& r) { return l.key < r.key; });
  const double dt = world.dt;
  for (size_t k = 0; k < contacts_.size(); ++k) {
    const XpbdContact& x = contacts_[k];
    const ContactKey key = KeyOf(substep_contacts_[k]);
    Vec3 impulse = Vec3::Zero();
    auto it = std::lower_bound(impulses_.begin(), impulses_.end(), key,
                               [](const KeyedImpulse& l, const ContactKey& r) { return l.key < r; });
    for (; it != impulses_.end() && it->key == key; ++it) impulse += it->impulse;
    Vec3 pa, pb;
    const double depth = XpbdContactDepth(x, world, &pa, &pb);
    if (depth <= 0.0 && impulse.isZero(0.0)) continue;
    Contact c = substep_contacts_[k];
    c.depth = depth;
    c.point = 0.5 * (pa + pb);
    c.normal_value = x.n.dot(impulse) / dt;
    c.tangent_value = (impulse - x.n * x.n.dot(impulse)) / dt;
    contacts_out->push_back(c);
    stats->max_penetration = std::max(stats->max_penetration, depth);
  }
}

StepStats XpbdMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  contacts_out->clear();
  const double dt = world.dt;
  const double h = dt / params_.substeps;
  const double alpha_tilde = params_.compliance / (h * h);
  const double joint_alpha_tilde = params_.joint_compliance / (h * h);
  const double threshold = std::max(params_.restitution_threshold, 2.0 * world.gravity.norm() * h);
  world.AccumulateForces();
  DetectAhead(world, detector, params_.margin, dt, &detected_);
  CandidatePairs();

  const bool project_joints =
      params_.joint_compliance == 0.0 && JointMassRatioAtLeast(world, params_.direct_mass_ratio);
  auto& bodies = world.bodies();
  start_.resize(bodies.size());
  predicted_.resize(bodies.size());
  impulses_.clear();
  for (int sub = 0; sub < params_.substeps; ++sub) {
    for (size_t i = 0; i < bodies.size(); ++i) start_[i] = {bodies[i].x, bodies[i].q};
    IntegrateMomenta(world, h);
    IntegratePositions(world, h);
    for (size_t i = 0; i < bodies.size(); ++i) predicted_[i] = {bodies[i].x, bodies[i].q};
    CollideCandidates(world);
    BeginXpbdSubstep(world, &contacts_);
    joint_lambdas_.assign(world.joints().size(), XpbdJointLambda{});
    for (int it = 0; it < params_.iterations; ++it) {
      SolveXpbdJoints(world, joint_alpha_tilde, &joint_lambdas_);
      SolveXpbdContactPositions(world, start_, h, alpha_tilde, &contacts_);
    }
    if (project_joints) ProjectJointPositions(world);
    stats.iterations += params_.iterations;
    // velocities from what the solve moved (Algorithm 2, v = (x - x_prev) / h)
    for (size_t i = 0; i < bodies.size(); ++i) {
      RigidBody& b = bodies[i];
      if (!b.IsDynamic()) continue;
      const Vec3 dx = b.x - predicted_[i].x;
      Quat dq = b.q * predicted_[i].q.conjugate();
      if (dx.isZero(0.0) && b.q.coeffs() == predicted_[i].q.coeffs()) continue;
      if (dq.w() < 0.0) dq.coeffs() = -dq.coeffs();
      b.P += b.mass * dx / h;
      b.L += b.InertiaWorld() * (2.0 / h * dq.vec());
    }
    SolveXpbdContactVelocities(world, h, threshold, &contacts_);
    for (size_t k = 0; k < contacts_.size(); ++k) {
      if (!contacts_[k].impulse.isZero(0.0)) impulses_.push_back({KeyOf(substep_contacts_[k]), contacts_[k].impulse});
    }
  }
  ReportContacts(world, contacts_out, &stats);
  world.FinishStep();
  stats.substeps = params_.substeps;
  stats.contacts = static_cast<int>(contacts_out->size());
  return stats;
}

}  // namespace contactsim
