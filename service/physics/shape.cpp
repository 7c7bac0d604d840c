#include "service/physics/shape.h"

#include <utility>

namespace contactsim {

const char* ShapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::kSphere: return "sphere";
    case ShapeType::kBox: return "box";
    case ShapeType::kCapsule: return "capsule";
    case ShapeType::kConvex: return "convex";
    case ShapeType::kPlane: return "plane";
    case ShapeType::kCompound: return "compound";
    case ShapeType::kMesh: return "mesh";
    case ShapeType::kHeightfield: return "heightfield";
    case ShapeType::kCount: break;
  }
  return "unknown";
}

Shape Shape::Sphere(double radius) {
  Shape s;
  s.type = ShapeType::kSphere;
  s.radius = radius;
  return s;
}

Shape Shape::Box(const Vec3& half_extents) {
  Shape s;
  s.type = ShapeType::kBox;
  s.half_extents = half_extents;
  return s;
}

Shape Shape::Capsule(double radius, double half_length) {
  Shape s;
  s.type = ShapeType::kCapsule;
  s.radius = radius;
  s.half_length = half_length;
  return s;
}

Shape Shape::Plane(const Vec3& normal, double offset) {
  Shape s;
  s.type = ShapeType::kPlane;
  s.plane_normal = normal.normalized();
  s.plane_offset = offset;
  return s;
}

Shape Shape::Convex(std::shared_ptr<const ConvexHull> hull) {
  Shape s;
  s.type = ShapeType::kConvex;
  s.hull = std::move(hull);
  return s;
}

Shape Shape::Compound(std::shared_ptr<const CompoundShape> compound) {
  Shape s;
  s.type = ShapeType::kCompound;
  s.compound = std::move(compound);
  return s;
}

Shape Shape::Compound(std::vector<ShapeChild> children) {
  auto compound = std::make_shared<CompoundShape>();
  compound->children = std::move(children);
  return Compound(std::shared_ptr<const CompoundShape>(std::move(compound)));
}

Shape Shape::Mesh(std::shared_ptr<const TriangleMesh> mesh) {
  Shape s;
  s.type = ShapeType::kMesh;
  s.mesh = std::move(mesh);
  return s;
}

Shape Shape::Heightfield(std::shared_ptr<const HeightField> heightfield) {
  Shape s;
  s.type = ShapeType::kHeightfield;
  s.heightfield = std::move(heightfield);
  return s;
}

}  // namespace contactsim
