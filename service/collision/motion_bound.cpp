#include "service/collision/motion_bound.h"

#include <algorithm>

#include "service/physics/convex_hull.h"

namespace contactsim {

double BoundingRadius(const Shape& s) {
  switch (s.type) {
    case ShapeType::kSphere: return s.radius;
    case ShapeType::kBox: return s.half_extents.norm();
    case ShapeType::kCapsule: return s.half_length + s.radius;
    case ShapeType::kConvex: {
      double r = 0.0;
      for (const Vec3& v : s.hull->vertices) r = std::max(r, v.norm());
      return r;
    }
    case ShapeType::kCompound: {
      double r = 0.0;
      for (const ShapeChild& c : s.compound->children) r = std::max(r, c.position.norm() + BoundingRadius(c.shape));
      return r;
    }
    default: return 0.0;
  }
}

BodyMotion MotionOf(const RigidBody& body) {
  BodyMotion m;
  m.v = body.LinearVelocity();
  m.accel = body.force * body.inv_mass;
  m.spin_reach = body.AngularVelocity().norm() * BoundingRadius(body.shape);
  return m;
}

double ClosingSpeedBound(const BodyMotion& a, const BodyMotion& b, double h) {
  const double accel = (a.accel - b.accel).norm() * h;
  return (a.v - b.v).norm() + accel + a.spin_reach + b.spin_reach;
}

double ClosingSpeedBound(const RigidBody& a, const RigidBody& b, double h) {
  return ClosingSpeedBound(MotionOf(a), MotionOf(b), h);
}

}  // namespace contactsim
