// Collision shapes, expressed in the body frame (origin at the centre of mass).
//
// A Shape is a small value type; the convex hull, which may be large, is
// shared between copies. Planes are half-spaces {p : n . p <= offset} in the
// body frame; the body is static, so for a plane at the identity pose the
// frame is the world frame.
#pragma once

#include <memory>
#include <string>

#include "service/physics/math.h"

namespace contactsim {

struct ConvexHull;  // service/physics/convex_hull.h

enum class ShapeType { kSphere = 0, kBox, kCapsule, kConvex, kPlane, kCount };

const char* ShapeTypeName(ShapeType type);

struct Shape {
  ShapeType type = ShapeType::kSphere;
  double radius = 0.0;              // m, sphere and capsule
  Vec3 half_extents = Vec3::Zero(); // m, box
  double half_length = 0.0;         // m, capsule: cap centres at (0, 0, +-half_length)
  Vec3 plane_normal = Vec3::UnitZ();// unit, plane: outward normal of the solid side's face
  double plane_offset = 0.0;        // m, plane: n . p = offset on the surface
  std::shared_ptr<const ConvexHull> hull;  // convex, vertices about the centre of mass

  static Shape Sphere(double radius);
  static Shape Box(const Vec3& half_extents);
  static Shape Capsule(double radius, double half_length);
  static Shape Plane(const Vec3& normal, double offset);
  static Shape Convex(std::shared_ptr<const ConvexHull> hull);

  bool IsPlane() const { return type == ShapeType::kPlane; }
};

}  // namespace contactsim
