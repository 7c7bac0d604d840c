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
    default: return 0.0;
  }
}

double ClosingSpeedBound(const RigidBody& a, const RigidBody& b, double h) {
  const double accel = (a.force * a.inv_mass - b.force * b.inv_mass).norm() * h;
  return (a.LinearVelocity() - b.LinearVelocity()).norm() + accel +
         a.AngularVelocity().norm() * BoundingRadius(a.shape) + b.AngularVelocity().norm() * BoundingRadius(b.shape);
}

}  // namespace contactsim
