// Bodies for contact-method tests, built through the same gate as commands
// and scene files (CreateBody), so tests exercise real validation.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "service/collision/narrowphase.h"
#include "service/physics/body_settings.h"
#include "service/physics/world.h"

namespace contactsim {
namespace testing {

// The material of settings that leave it unset: restitution 0.5, the
// engine's default when these scenarios and their measurements were made.
inline constexpr Material kScenarioMaterial{0.5, 0.5};

inline BodyId AddValidBody(World& world, const BodySettings& s) {
  RigidBody b;
  const Status st = CreateBody(s, kScenarioMaterial, &b);
  EXPECT_TRUE(st.ok()) << st.message();
  return world.AddBody(b);
}

inline BodyId AddGround(World& world, double restitution, double friction) {
  BodySettings s;
  s.shape = ShapeType::kPlane;
  s.restitution = restitution;
  s.friction = friction;
  return AddValidBody(world, s);
}

inline BodyId AddSphere(World& world, double radius, const Vec3& p, double restitution, double friction = 0.5,
                        const Vec3& v = Vec3::Zero()) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = radius;
  s.position = p;
  s.linear_velocity = v;
  s.restitution = restitution;
  s.friction = friction;
  return AddValidBody(world, s);
}

inline BodyId AddBox(World& world, const Vec3& half, const Vec3& p, double restitution, double friction,
                     const Vec3& v = Vec3::Zero()) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = half;
  s.position = p;
  s.linear_velocity = v;
  s.restitution = restitution;
  s.friction = friction;
  return AddValidBody(world, s);
}

// A cube of half size `half`.
inline BodyId AddBox(World& world, double half, const Vec3& p, double restitution, double friction,
                     const Vec3& v = Vec3::Zero()) {
  return AddBox(world, Vec3::Constant(half), p, restitution, friction, v);
}

// Kinetic plus gravitational potential energy of the dynamic bodies (J).
inline double MechanicalEnergy(const World& world) { return KineticEnergy(world) + PotentialEnergy(world); }

// Smallest signed distance (m) between two bodies (one of them dynamic) by
// the narrowphase: exact for planes and spheres, a lower bound for two
// polyhedra, so > 0 means apart.
inline double SmallestGap(const World& world) {
  double gap = std::numeric_limits<double>::infinity();
  const auto& b = world.bodies();
  for (size_t i = 0; i < b.size(); ++i) {
    for (size_t j = i + 1; j < b.size(); ++j) {
      if (!b[i].IsDynamic() && !b[j].IsDynamic()) continue;
      gap = std::min(gap, PairSignedDistance(b[i], b[j], 1.0));
    }
  }
  return gap;
}

}  // namespace testing
}  // namespace contactsim
