// Exact intersection of a ray with one shape, in the shape's body frame.
//
// Every shape is a closed convex solid (a plane: its half-space), so the
// points of a ray inside it form one interval [t_in, t_out]. A ray whose
// origin lies inside the solid or on its surface (t_in <= 0 <= t_out)
// answers kInside: the caller reports a hit at distance 0 with the normal
// against the ray (as PhysX reports an initial overlap), so that a range
// sensor buried in a wall reads 0 rather than its maximum range. Otherwise
// the ray hits at t_in when 0 < t_in <= max_distance, with the outward
// normal of the surface there. A triangle mesh or heightfield is a surface,
// not a solid: a ray hits the front of its nearest triangle and passes
// through a back face (a static floor seen from below).
#pragma once

#include "service/physics/math.h"
#include "service/physics/shape.h"

namespace contactsim {

enum class RayShapeResult { kMiss, kHit, kInside };

struct RayShapeHit {
  double t = 0.0;               // m along the unit direction; 0 for kInside
  Vec3 normal = Vec3::Zero();   // unit, body frame, outward; unset for kInside
};

// `origin` and `direction` (unit) in the body frame; max_distance >= 0.
RayShapeResult RayCastShape(const Shape& shape, const Vec3& origin, const Vec3& direction, double max_distance,
                            RayShapeHit* hit);

}  // namespace contactsim
