// Collision shapes, expressed in the body frame (origin at the centre of mass).
//
// A Shape is a small value type; the convex hull, which may be large, is
// shared between copies. Planes are half-spaces {p : n . p <= offset} in the
// body frame; the body is static, so for a plane at the identity pose the
// frame is the world frame.
//
// A compound holds several shapes at fixed poses in the body frame (a robot
// link with several collision elements, or one shape whose centre is not
// the body's centre of mass): the body collides as the union of its
// children, each child collided as its own shape (docs/physics.md,
// "Compound bodies and mass properties").
//
// A triangle mesh or a heightfield is a static surface (docs/physics.md,
// "Triangle meshes and heightfields"). Their geometry and its bounding-volume
// tree belong to the collision layer (service/collision/triangle_mesh.h,
// height_field.h), which builds them before the body is created; the
// physics layer only carries them, as it carries a hull.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "service/physics/math.h"

namespace contactsim {

struct ConvexHull;  // service/physics/convex_hull.h
struct TriangleMesh;  // service/collision/triangle_mesh.h
struct HeightField;   // service/collision/height_field.h
struct CompoundShape;
struct ShapeChild;

enum class ShapeType { kSphere = 0, kBox, kCapsule, kConvex, kPlane, kCompound, kMesh, kHeightfield, kCount };

const char* ShapeTypeName(ShapeType type);

struct Shape {
  ShapeType type = ShapeType::kSphere;
  double radius = 0.0;              // m, sphere and capsule
  Vec3 half_extents = Vec3::Zero(); // m, box
  double half_length = 0.0;         // m, capsule: cap centres at (0, 0, +-half_length)
  Vec3 plane_normal = Vec3::UnitZ();// unit, plane: outward normal of the solid side's face
  double plane_offset = 0.0;        // m, plane: n . p = offset on the surface
  std::shared_ptr<const ConvexHull> hull;  // convex, vertices about the centre of mass
  std::shared_ptr<const CompoundShape> compound;  // compound, children posed in the body frame
  std::shared_ptr<const TriangleMesh> mesh;        // mesh, triangles in the body frame
  std::shared_ptr<const HeightField> heightfield;  // heightfield, grid centred on the body origin

  static Shape Sphere(double radius);
  static Shape Box(const Vec3& half_extents);
  static Shape Capsule(double radius, double half_length);
  static Shape Plane(const Vec3& normal, double offset);
  static Shape Convex(std::shared_ptr<const ConvexHull> hull);
  static Shape Compound(std::shared_ptr<const CompoundShape> compound);
  static Shape Compound(std::vector<ShapeChild> children);
  static Shape Mesh(std::shared_ptr<const TriangleMesh> mesh);
  static Shape Heightfield(std::shared_ptr<const HeightField> heightfield);

  bool IsPlane() const { return type == ShapeType::kPlane; }
  bool IsCompound() const { return type == ShapeType::kCompound; }
  // a static surface of triangles: a mesh or a heightfield
  bool IsTriangleSurface() const { return type == ShapeType::kMesh || type == ShapeType::kHeightfield; }
};

// One shape of a compound: a sphere, box, capsule or convex hull (never a
// plane or another compound), at `position` (m) turned by `orientation`
// (child to body) in the body frame, whose origin is the centre of mass.
struct ShapeChild {
  Shape shape;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

struct CompoundShape {
  std::vector<ShapeChild> children;
};

}  // namespace contactsim
