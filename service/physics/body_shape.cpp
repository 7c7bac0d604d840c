#include "service/physics/body_shape.h"

#include "service/physics/convex_hull.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

Status CheckLength(const std::string& field, double v, bool zero_ok) {
  Status st = zero_ok ? CheckNonNegative(field, v) : CheckPositive(field, v);
  if (!st.ok()) return st;
  return CheckInRange(field, v, 0.0, kMaxLength);
}

// One solid shape from its fields; `prefix` names the fields ("" or
// "parts[2]."). A hull's child sits at its centroid, the rest at the origin.
Status MakeSolid(const std::string& prefix, ShapeType type, double radius, const Vec3& half_extents,
                 double half_length, const std::vector<Vec3>& points, HullMemo* memo, ShapeChild* child) {
  Status st;
  *child = ShapeChild();
  switch (type) {
    case ShapeType::kSphere:
      if (!(st = CheckLength(prefix + "radius", radius, false)).ok()) return st;
      child->shape = Shape::Sphere(radius);
      return Status::Ok();
    case ShapeType::kBox:
      for (int i = 0; i < 3; ++i) {
        const std::string field = prefix + "half_extents[" + char('0' + i) + "]";
        if (!(st = CheckLength(field, half_extents[i], false)).ok()) return st;
      }
      child->shape = Shape::Box(half_extents);
      return Status::Ok();
    case ShapeType::kCapsule:
      if (!(st = CheckLength(prefix + "radius", radius, false)).ok()) return st;
      if (!(st = CheckLength(prefix + "half_length", half_length, true)).ok()) return st;
      child->shape = Shape::Capsule(radius, half_length);
      return Status::Ok();
    case ShapeType::kConvex: {
      for (size_t i = 0; i < points.size(); ++i) {
        if (!(st = CheckFinite(prefix + "points[" + std::to_string(i) + "]", points[i])).ok()) return st;
      }
      std::shared_ptr<const ConvexHull> hull;
      st = memo != nullptr ? memo->Hull(points, &hull, &child->position)
                           : BuildConvexHull(points, &hull, &child->position);
      if (!st.ok()) {
        return prefix.empty() ? st : Status::InvalidArgument(prefix + "points: " + st.message());
      }
      child->shape = Shape::Convex(hull);
      return Status::Ok();
    }
    default: break;
  }
  return Status::InvalidArgument(prefix + "type must be sphere, box, capsule or convex, got " +
                                 (type >= ShapeType::kSphere && type < ShapeType::kCount
                                      ? std::string(ShapeTypeName(type))
                                      : "type " + std::to_string(static_cast<int>(type))));
}

Status MakePartChild(const ShapePart& part, int index, HullMemo* memo, ShapeChild* child) {
  const std::string prefix = "parts[" + std::to_string(index) + "].";
  Status st =
      MakeSolid(prefix, part.type, part.radius, part.half_extents, part.half_length, part.points, memo, child);
  if (!st.ok()) return st;
  if (!(st = CheckFinite(prefix + "position", part.position)).ok()) return st;
  if (!(st = CheckInRange(prefix + "position", part.position.cwiseAbs().maxCoeff(), 0.0, kMaxLength)).ok()) {
    return st;
  }
  const Eigen::Vector4d wxyz(part.orientation.w(), part.orientation.x(), part.orientation.y(), part.orientation.z());
  Quat q;
  if (!(st = MakeOrientation(prefix + "orientation", wxyz, false, &q)).ok()) return st;
  // the hull's centroid, posed in the settings' frame
  child->position = part.position + q * child->position;
  child->orientation = q;
  return Status::Ok();
}

}  // namespace

Status MakeFrameChildren(const BodySettings& s, std::vector<ShapeChild>* children, HullMemo* memo) {
  children->clear();
  if (s.shape != ShapeType::kCompound) {
    if (!s.parts.empty()) {
      return Status::InvalidArgument("parts are for a compound shape, got " + std::to_string(s.parts.size()) +
                                     " part(s) on a " + ShapeTypeName(s.shape));
    }
    ShapeChild child;
    Status st = MakeSolid("", s.shape, s.radius, s.half_extents, s.half_length, s.points, memo, &child);
    if (!st.ok()) {
      return s.shape == ShapeType::kPlane || s.shape >= ShapeType::kCount
                 ? Status::InvalidArgument("shape must be sphere, box, capsule, convex, plane or compound, got type " +
                                           std::to_string(static_cast<int>(s.shape)))
                 : st;
    }
    children->push_back(child);
    return Status::Ok();
  }
  const int n = static_cast<int>(s.parts.size());
  if (n < 1 || n > kMaxShapeParts) {
    return Status::InvalidArgument("a compound takes 1 to " + std::to_string(kMaxShapeParts) + " parts, got " +
                                   std::to_string(n));
  }
  for (int i = 0; i < n; ++i) {
    ShapeChild child;
    Status st = MakePartChild(s.parts[i], i, memo, &child);
    if (!st.ok()) {
      children->clear();
      return st;
    }
    children->push_back(child);
  }
  return Status::Ok();
}

Shape PlaceChildren(const BodySettings& s, const std::vector<ShapeChild>& children, const Vec3& com) {
  const bool lone = s.shape != ShapeType::kCompound && children.size() == 1;
  if (lone && children[0].position == com && children[0].orientation.coeffs() == Quat::Identity().coeffs()) {
    return children[0].shape;
  }
  std::vector<ShapeChild> placed = children;
  for (ShapeChild& child : placed) child.position -= com;
  return Shape::Compound(std::move(placed));
}

}  // namespace contactsim
