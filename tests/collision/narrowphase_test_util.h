// Bodies, random poses and hulls shared by the narrowphase tests.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "service/collision/contact.h"
#include "service/physics/convex_hull.h"
#include "service/physics/rigid_body.h"

namespace contactsim {
namespace testing_util {

// Distances and depths equal to round-off of ~1 m coordinates (m).
inline constexpr double kTol = 1e-12;

inline RigidBody MakeBody(BodyId id, const Shape& shape, const Vec3& x = Vec3::Zero(),
                          const Quat& q = Quat::Identity()) {
  RigidBody body;
  body.id = id;
  body.shape = shape;
  body.x = x;
  body.q = q.normalized();
  return body;
}

inline RigidBody Sphere(BodyId id, double r, const Vec3& x) { return MakeBody(id, Shape::Sphere(r), x); }

inline RigidBody Box(BodyId id, const Vec3& h, const Vec3& x, const Quat& q = Quat::Identity()) {
  return MakeBody(id, Shape::Box(h), x, q);
}

inline RigidBody Capsule(BodyId id, double r, double half_length, const Vec3& x,
                         const Quat& q = Quat::Identity()) {
  return MakeBody(id, Shape::Capsule(r, half_length), x, q);
}

// z = 0 ground, solid below
inline RigidBody Ground(BodyId id) { return MakeBody(id, Shape::Plane(Vec3::UnitZ(), 0.0)); }

// Hull of the given points (centred at its centre of mass); aborts the test
// binary on failure, which would be a bug in the hull builder.
inline std::shared_ptr<const ConvexHull> Hull(const std::vector<Vec3>& points) {
  std::shared_ptr<const ConvexHull> hull;
  const Status status = BuildConvexHull(points, &hull);
  if (!status.ok()) std::abort();
  return hull;
}

// An irregular 12-point hull about 0.3 m across.
inline std::shared_ptr<const ConvexHull> RockHull() {
  return Hull({{0.3, 0.0, 0.0},   {-0.25, 0.05, 0.02}, {0.0, 0.28, -0.05}, {0.02, -0.3, 0.04},
               {0.05, 0.02, 0.26}, {-0.03, 0.0, -0.31}, {0.18, 0.17, 0.15}, {-0.16, -0.2, 0.12},
               {0.2, -0.15, -0.18}, {-0.19, 0.21, -0.12}, {0.12, 0.22, -0.2}, {-0.1, -0.12, -0.22}});
}

inline RigidBody Convex(BodyId id, std::shared_ptr<const ConvexHull> hull, const Vec3& x,
                        const Quat& q = Quat::Identity()) {
  return MakeBody(id, Shape::Convex(std::move(hull)), x, q);
}

inline Quat RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Quat q{n(rng), n(rng), n(rng), n(rng)};
  return q.normalized();
}

inline Vec3 RandomVector(std::mt19937_64& rng, double half_width) {
  std::uniform_real_distribution<double> u(-half_width, half_width);
  return Vec3{u(rng), u(rng), u(rng)};
}

inline double MaxDepth(const ContactSet& contacts) {
  double d = -1e300;
  for (const Contact& c : contacts) d = std::max(d, c.depth);
  return d;
}

}  // namespace testing_util
}  // namespace contactsim
