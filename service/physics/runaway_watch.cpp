#include "service/physics/runaway_watch.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace contactsim {
namespace {

constexpr double kScaleSpeed = 1.0;   // m/s, v_s
constexpr double kScaleHeight = 1.0;  // m, l_s

bool StateIsFinite(const RigidBody& b) { return IsFinite(b.x) && IsFinite(b.q) && IsFinite(b.P) && IsFinite(b.L); }

double MechanicalEnergy(const World& world) { return KineticEnergy(world) + PotentialEnergy(world); }

// Fastest speed of a kinematic body (m/s): what it can hand on.
double KinematicSpeed(const World& world) {
  double v = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.motion == MotionType::kKinematic) v = std::max(v, b.LinearVelocity().norm());
  }
  return v;
}

std::string Describe(const char* what, const RigidBody& b, double value, const char* unit) {
  char text[160];
  std::snprintf(text, sizeof text, "body %lld %s %.3g %s", static_cast<long long>(b.id), what, value, unit);
  return text;
}

}  // namespace

void RunawayWatch::Rebase(const World& world) {
  double mass = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic() && StateIsFinite(b)) mass += b.mass;
  }
  base_energy_ = MechanicalEnergy(world);
  scale_ = KineticEnergy(world) + mass * (0.5 * kScaleSpeed * kScaleSpeed + world.gravity.norm() * kScaleHeight);
  work_ = 0.0;
  based_ = std::isfinite(base_energy_) && std::isfinite(scale_);
}

void RunawayWatch::BeforeStep(const World& world) {
  if (!based_) Rebase(world);
  before_.resize(world.bodies().size());
  for (size_t i = 0; i < before_.size(); ++i) before_[i] = world.bodies()[i].x;
}

Status RunawayWatch::AfterStep(const World& world) {
  const auto& bodies = world.bodies();
  const double kinematic = KinematicSpeed(world);
  double fastest = -1.0;
  const RigidBody* fast = nullptr;
  double kinetic = 0.0;  // KineticEnergy(world), each body's w taken once for it and the work
  for (size_t i = 0; i < bodies.size(); ++i) {
    const RigidBody& b = bodies[i];
    if (!StateIsFinite(b)) {
      return Status::FailedPrecondition("the world blew up at step " + std::to_string(world.step) + ": " +
                                        Describe("has a non-finite state, |x| =", b, b.x.norm(), "m"));
    }
    if (!b.IsDynamic()) continue;
    const Vec3 w = b.AngularVelocity();
    kinetic += 0.5 * b.P.squaredNorm() * b.inv_mass + 0.5 * b.L.dot(w);  // RigidBody::KineticEnergy
    if (i >= before_.size() || bodies.size() != before_.size()) continue;
    // the work of the body's force (gravity's is in V) and torque over the step
    const Vec3 applied = b.force - b.mass * world.gravity;
    work_ += std::abs(applied.dot(b.x - before_[i])) + std::abs(b.torque.dot(w)) * world.dt;
    work_ += 2.0 * b.mass * kinematic * kinematic;
    const double speed = b.LinearVelocity().norm();
    if (speed > fastest) fastest = speed, fast = &b;
  }
  const double gain = kinetic + PotentialEnergy(world) - base_energy_ - work_;
  if (based_ && gain > factor_ * scale_) {
    char text[200];
    std::snprintf(text, sizeof text, "the world blew up at step %lld: its energy rose %.3g J beyond what it had and "
                  "was given (bound %.3g J); ", static_cast<long long>(world.step), gain, factor_ * scale_);
    return Status::FailedPrecondition(text + (fast ? Describe("moves at", *fast, fastest, "m/s") : std::string()));
  }
  return Status::Ok();
}

}  // namespace contactsim
