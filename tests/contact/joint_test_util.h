// Jointed scenes for the joint tests: a stepper over any contact method and
// builders for pendulums and chains (through World::AddJoint, the same gate
// as commands and scene files).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

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

// Period (s) from the times at which x crosses zero upwards or downwards,
// linearly interpolated between steps: twice the mean spacing of the
// crossings between the first and the last.
inline double MeasurePeriod(MethodSim& sim, BodyId bob, double duration) {
  std::vector<double> crossings;
  double last_x = sim.world.Find(bob)->x.x();
  double last_t = sim.world.time;
  while (sim.world.time < duration) {
    sim.Step();
    const double x = sim.world.Find(bob)->x.x();
    if ((last_x < 0.0) != (x < 0.0)) crossings.push_back(last_t + (sim.world.time - last_t) * last_x / (last_x - x));
    last_x = x;
    last_t = sim.world.time;
  }
  if (crossings.size() < 2) return 0.0;
  return 2.0 * (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

// Kinetic plus gravitational potential energy of every dynamic body (J).
// Energy errors of a run, relative to the energy above the hanging rest
// state (the part that moves, independent of the height datum).
struct EnergyRecord {
  double worst = 0.0;       // largest |E - E0|
  double final = 0.0;       // E - E0 at the end (negative: lost)
  double above_rest = 0.0;  // J, E0 minus the rest state's energy
};

// A double pendulum (spheres of radius 0.05 m on distance joints, 1 m from
// `pivot` and 0.7 m further out, both arms released horizontal: chaotic
// motion) run for `seconds`.
inline EnergyRecord RunDoublePendulum(JointSim& sim, const Vec3& pivot, double seconds) {
  const double l1 = 1.0, l2 = 0.7, r = 0.05;
  const BodyId b1 = AddSphere(sim.world, r, pivot + Vec3(l1, 0, 0), 0.0);
  const BodyId b2 = AddSphere(sim.world, r, pivot + Vec3(l1, 0, -l2), 0.0);
  AddJoint(sim.world, JointKind::kDistance, b1, kWorldBody, pivot);
  AddJoint(sim.world, JointKind::kDistance, b2, b1, sim.world.Find(b1)->x);
  const double m1 = sim.world.Find(b1)->mass, m2 = sim.world.Find(b2)->mass;
  const double e0 = MechanicalEnergy(sim.world);
  const double rest = -kG * (m1 * l1 + m2 * (l1 + l2)) + kG * (m1 + m2) * pivot.z();
  EnergyRecord out;
  out.above_rest = e0 - rest;
  while (sim.world.time < seconds) {
    sim.Step();
    out.final = (MechanicalEnergy(sim.world) - e0) / out.above_rest;
    out.worst = std::max(out.worst, std::abs(out.final));
  }
  return out;
}

// A chain of n capsules (radius r, half length hl) laid out from `top`
// along the unit direction `along`, the first joined to the world by a ball
// joint at `top`, each joined to the next by a ball joint at their touching
// cap tips. Returns the link ids, top first.
inline std::vector<BodyId> AddChain(World& world, int n, const Vec3& top, const Vec3& along, double r, double hl) {
  std::vector<BodyId> links;
  const double pitch = 2.0 * (hl + r);  // tip to tip
  const Quat turn = Quat::FromTwoVectors(Vec3(0, 0, -1), along);  // the capsule's axis is its z
  for (int i = 0; i < n; ++i) {
    BodySettings s;
    s.shape = ShapeType::kCapsule;
    s.radius = r;
    s.half_length = hl;
    s.position = top + (i + 0.5) * pitch * along;
    s.orientation = Eigen::Vector4d(turn.w(), turn.x(), turn.y(), turn.z());
    links.push_back(AddValidBody(world, s));
    const BodyId above = i == 0 ? kWorldBody : links[i - 1];
    AddJoint(world, JointKind::kBall, links[i], above, top + i * pitch * along);
  }
  return links;
}

// The chain of AddChain hanging straight down.
inline std::vector<BodyId> AddHangingChain(World& world, int n, const Vec3& top, double r, double hl) {
  return AddChain(world, n, top, Vec3(0, 0, -1), r, hl);
}

// Largest separation (m) of a joint's two anchors over the world's joints.
inline double MaxAnchorSeparation(const World& world) {
  double worst = 0.0;
  for (const Joint& j : world.joints()) {
    const RigidBody* a = world.Find(j.body_a);
    const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
    worst = std::max(worst, (AnchorWorld(j.anchor_a, a) - AnchorWorld(j.anchor_b, b)).norm());
  }
  return worst;
}

}  // namespace testing
}  // namespace contactsim
