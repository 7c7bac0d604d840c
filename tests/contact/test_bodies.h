// Bodies for contact-method tests, built through the same gate as commands
// and scene files (CreateBody), so tests exercise real validation.
#pragma once

#include <gtest/gtest.h>

#include "service/physics/body_settings.h"
#include "service/physics/world.h"

namespace contactsim {
namespace testing {

inline BodyId AddValidBody(World& world, const BodySettings& s) {
  RigidBody b;
  const Status st = CreateBody(s, Material{}, &b);
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

}  // namespace testing
}  // namespace contactsim
