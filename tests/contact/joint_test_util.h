// Jointed scenes for the joint tests: a stepper over any contact method and
// builders for pendulums and chains (through World::AddJoint, the same gate
// as commands and scene files).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "service/contact/contact_method.h"
#include "service/physics/body_settings.h"
#include "service/physics/world.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace testing {

constexpr double kG = 9.81;  // m/s^2, World::DefaultGravity

// A contact method named by `spec`: a method name, or "lcp:pgs" /
// "lcp:lemke" for the lcp method with that solver.
struct JointSim : MethodSim {
  explicit JointSim(const std::string& spec) : MethodSim(MethodOf(spec), SolverOf(spec)) {}
  static std::string MethodOf(const std::string& spec) { return spec.substr(0, spec.find(':')); }
  static ParamMap SolverOf(const std::string& spec) {
    const size_t colon = spec.find(':');
    if (colon == std::string::npos) return {};
    return {{"solver", spec.substr(colon + 1)}};
  }
};

inline JointId AddJoint(World& world, const JointSettings& s) {
  JointId id = 0;
  const Status st = world.AddJoint(s, &id);
  EXPECT_TRUE(st.ok()) << st.message();
  return id;
}

inline JointId AddJoint(World& world, JointKind kind, BodyId a, BodyId b, const Vec3& anchor) {
  JointSettings s;
  s.kind = kind;
  s.body_a = a;
  s.body_b = b;
  s.anchor = anchor;
  return AddJoint(world, s);
}

inline JointId AddHinge(World& world, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
                        std::optional<std::pair<double, double>> limits = std::nullopt) {
  JointSettings s;
  s.kind = JointKind::kHinge;
  s.body_a = a;
  s.body_b = b;
  s.anchor = anchor;
  s.axis = axis;
  s.limits = limits;
  return AddJoint(world, s);
}

// Kinetic plus gravitational potential energy of every dynamic body (J).
inline double MechanicalEnergy(const World& world) {
  double e = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic()) e += b.KineticEnergy() - b.mass * world.gravity.dot(b.x);
  }
  return e;
}

// A chain of n capsules (radius r, half length hl) hanging straight down from
// a ball joint to the world at `top`, each joined to the next by a ball joint
// at their touching cap tips. Returns the link ids, top first.
inline std::vector<BodyId> AddHangingChain(World& world, int n, const Vec3& top, double r, double hl) {
  std::vector<BodyId> links;
  const double pitch = 2.0 * (hl + r);  // tip to tip
  for (int i = 0; i < n; ++i) {
    BodySettings s;
    s.shape = ShapeType::kCapsule;
    s.radius = r;
    s.half_length = hl;
    s.position = top - Vec3(0, 0, (i + 0.5) * pitch);
    links.push_back(AddValidBody(world, s));
    const BodyId above = i == 0 ? kWorldBody : links[i - 1];
    AddJoint(world, JointKind::kBall, links[i], above, top - Vec3(0, 0, i * pitch));
  }
  return links;
}

}  // namespace testing
}  // namespace contactsim
