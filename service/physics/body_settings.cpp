#include "service/physics/body_settings.h"

#include "service/physics/convex_hull.h"
#include "service/physics/mass_properties.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

// Largest size or speed we accept; beyond it double precision and the
// broadphase stop being meaningful.
constexpr double kMaxLength = 1e6;  // m

Status MakeShape(const BodySettings& s, Shape* shape, Vec3* origin_offset) {
  Status st;
  *origin_offset = Vec3::Zero();
  switch (s.shape) {
    case ShapeType::kSphere:
      if (!(st = CheckPositive("radius", s.radius)).ok()) return st;
      if (!(st = CheckInRange("radius", s.radius, 0.0, kMaxLength)).ok()) return st;
      *shape = Shape::Sphere(s.radius);
      return Status::Ok();
    case ShapeType::kBox:
      for (int i = 0; i < 3; ++i) {
        const std::string field = std::string("half_extents[") + char('0' + i) + "]";
        if (!(st = CheckPositive(field, s.half_extents[i])).ok()) return st;
        if (!(st = CheckInRange(field, s.half_extents[i], 0.0, kMaxLength)).ok()) return st;
      }
      *shape = Shape::Box(s.half_extents);
      return Status::Ok();
    case ShapeType::kCapsule:
      if (!(st = CheckPositive("radius", s.radius)).ok()) return st;
      if (!(st = CheckNonNegative("half_length", s.half_length)).ok()) return st;
      if (!(st = CheckInRange("radius", s.radius, 0.0, kMaxLength)).ok()) return st;
      if (!(st = CheckInRange("half_length", s.half_length, 0.0, kMaxLength)).ok()) return st;
      *shape = Shape::Capsule(s.radius, s.half_length);
      return Status::Ok();
    case ShapeType::kPlane: {
      if (!(st = CheckFinite("plane_normal", s.plane_normal)).ok()) return st;
      if (s.plane_normal.norm() < 1e-9) {
        return Status::InvalidArgument("plane_normal must be a non-zero vector, got " + FormatValue(s.plane_normal));
      }
      if (!(st = CheckFinite("plane_offset", s.plane_offset)).ok()) return st;
      *shape = Shape::Plane(s.plane_normal, s.plane_offset);
      return Status::Ok();
    }
    case ShapeType::kConvex: {
      for (size_t i = 0; i < s.points.size(); ++i) {
        if (!(st = CheckFinite("points[" + std::to_string(i) + "]", s.points[i])).ok()) return st;
      }
      std::shared_ptr<const ConvexHull> hull;
      Vec3 centroid;
      if (!(st = BuildConvexHull(s.points, &hull, &centroid)).ok()) return st;
      *shape = Shape::Convex(hull);
      *origin_offset = centroid;
      return Status::Ok();
    }
    case ShapeType::kCount: break;
  }
  return Status::InvalidArgument("shape must be sphere, box, capsule, convex or plane, got type " +
                                 std::to_string(static_cast<int>(s.shape)));
}

}  // namespace

Status CheckMaterial(std::optional<double> restitution, std::optional<double> friction) {
  Status st;
  if (restitution && !(st = CheckInRange("restitution", *restitution, 0.0, 1.0)).ok()) return st;
  if (friction && !(st = CheckInRange("friction", *friction, 0.0, 100.0)).ok()) return st;
  return Status::Ok();
}

Status CreateBody(const BodySettings& s, const Material& default_material, RigidBody* body) {
  Status st;
  Shape shape;
  Vec3 origin_offset;
  if (!(st = MakeShape(s, &shape, &origin_offset)).ok()) return st;
  if (!(st = CheckFinite("position", s.position)).ok()) return st;
  if (!(st = CheckInRange("position", s.position.cwiseAbs().maxCoeff(), 0.0, kMaxLength)).ok()) return st;
  if (!(st = CheckFinite("linear_velocity", s.linear_velocity)).ok()) return st;
  if (!(st = CheckFinite("angular_velocity", s.angular_velocity)).ok()) return st;
  Quat q;
  if (!(st = MakeOrientation("orientation", s.orientation, true, &q)).ok()) return st;
  if (!(st = CheckMaterial(s.restitution, s.friction)).ok()) return st;
  if (s.kinematic && s.fixed) {
    return Status::InvalidArgument("a body is fixed or kinematic, not both (kinematic true, fixed true)");
  }
  if (s.kinematic && s.shape == ShapeType::kPlane) {
    return Status::InvalidArgument("a plane is always static (kinematic true)");
  }
  // kinematic bodies are infinite-mass like static ones; only their motion differs
  const bool is_static = s.fixed || s.kinematic || s.shape == ShapeType::kPlane;
  if (s.mass && s.density) {
    return Status::InvalidArgument("give mass or density, not both (mass " + FormatValue(*s.mass) + ", density " +
                                   FormatValue(*s.density) + ")");
  }
  if (!is_static) {
    if (s.mass && !(st = CheckPositive("mass", *s.mass)).ok()) return st;
    if (s.density && !(st = CheckPositive("density", *s.density)).ok()) return st;
  }

  RigidBody b;
  b.name = s.name;
  b.shape = shape;
  b.material = default_material;
  if (s.restitution) b.material.restitution = *s.restitution;
  if (s.friction) b.material.friction = *s.friction;
  b.collision_category = s.collision_category;
  b.collision_mask = s.collision_mask;
  b.collision_group = s.collision_group;
  b.q = q;
  b.x = s.position + q * origin_offset;
  if (is_static) {
    b.MakeStatic();
    if (s.kinematic) b.motion = MotionType::kKinematic;
  } else if (s.mass) {
    b.SetMass(*s.mass);
  } else {
    b.SetMassFromDensity(s.density.value_or(kDefaultDensity));
  }
  b.SetVelocity(s.linear_velocity, s.angular_velocity);
  *body = std::move(b);
  return Status::Ok();
}

}  // namespace contactsim
