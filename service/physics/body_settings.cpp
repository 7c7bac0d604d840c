#include "service/physics/body_settings.h"

#include "service/physics/body_shape.h"
#include "service/physics/mass_properties.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

Status MakePlane(const BodySettings& s, Shape* shape) {
  Status st;
  if (!(st = CheckFinite("plane_normal", s.plane_normal)).ok()) return st;
  if (s.plane_normal.norm() < 1e-9) {
    return Status::InvalidArgument("plane_normal must be a non-zero vector, got " + FormatValue(s.plane_normal));
  }
  if (!(st = CheckFinite("plane_offset", s.plane_offset)).ok()) return st;
  *shape = Shape::Plane(s.plane_normal, s.plane_offset);
  return Status::Ok();
}

bool IsSurface(ShapeType type) { return type == ShapeType::kMesh || type == ShapeType::kHeightfield; }

// A mesh or heightfield arrives built (its checks are the collision
// layer's); here only that it is there and is the only geometry given.
Status MakeSurface(const BodySettings& s, Shape* shape) {
  const char* name = ShapeTypeName(s.shape);
  if (!s.parts.empty()) return Status::InvalidArgument(std::string("parts are for a compound shape, got them on a ") + name);
  if (s.shape == ShapeType::kMesh) {
    if (s.mesh == nullptr) return Status::InvalidArgument("a mesh body needs its triangles");
    *shape = Shape::Mesh(s.mesh);
  } else {
    if (s.heightfield == nullptr) return Status::InvalidArgument("a heightfield body needs its heights");
    *shape = Shape::Heightfield(s.heightfield);
  }
  return Status::Ok();
}

// The explicit mass properties' own checks (the inertia needs a mass to
// go with it; a plane has none).
Status CheckExplicitMass(const BodySettings& s) {
  Status st;
  if ((s.shape == ShapeType::kPlane || IsSurface(s.shape)) && (s.center_of_mass || s.inertia)) {
    return Status::InvalidArgument(std::string("a ") + ShapeTypeName(s.shape) +
                                   " has no mass properties (center_of_mass or inertia given)");
  }
  if (s.center_of_mass) {
    if (!(st = CheckFinite("center_of_mass", *s.center_of_mass)).ok()) return st;
    if (!(st = CheckInRange("center_of_mass", s.center_of_mass->cwiseAbs().maxCoeff(), 0.0, kMaxLength)).ok()) {
      return st;
    }
  }
  if (s.inertia) {
    if (!s.mass) return Status::InvalidArgument("an explicit inertia needs an explicit mass, got none");
    if (!(st = CheckInertiaTensor("inertia", *s.inertia)).ok()) return st;
  }
  return Status::Ok();
}

// The shape posed about its centre of mass, the body's origin: `com`
// receives that centre in the settings' frame (the explicit one, else the
// shape's at uniform density).
Status MakeShape(const BodySettings& s, HullMemo* memo, Shape* shape, Vec3* com) {
  *com = Vec3::Zero();
  if (s.shape == ShapeType::kPlane) {
    if (!s.parts.empty()) return Status::InvalidArgument("parts are for a compound shape, got them on a plane");
    return MakePlane(s, shape);
  }
  if (IsSurface(s.shape)) {
    *com = Vec3::Zero();
    return MakeSurface(s, shape);
  }
  std::vector<ShapeChild> children;
  Status st = MakeFrameChildren(s, &children, memo);
  if (!st.ok()) return st;
  if (s.center_of_mass) {
    *com = *s.center_of_mass;
  } else if (s.shape == ShapeType::kCompound) {
    *com = ComputeMassProperties(Shape::Compound(children), 1.0).center;
  } else {
    *com = children[0].position;  // a hull's centroid, or the origin
  }
  *shape = PlaceChildren(s, children, *com);
  return Status::Ok();
}

}  // namespace

Status CheckMaterial(std::optional<double> restitution, std::optional<double> friction) {
  Status st;
  if (restitution && !(st = CheckInRange("restitution", *restitution, 0.0, 1.0)).ok()) return st;
  if (friction && !(st = CheckInRange("friction", *friction, 0.0, 100.0)).ok()) return st;
  return Status::Ok();
}

Status CreateBody(const BodySettings& s, const Material& default_material, RigidBody* body, HullMemo* memo) {
  Status st;
  Shape shape;
  Vec3 com;
  if (!(st = CheckExplicitMass(s)).ok()) return st;
  if (!(st = MakeShape(s, memo, &shape, &com)).ok()) return st;
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
  if (s.kinematic && (s.shape == ShapeType::kPlane || IsSurface(s.shape))) {
    return Status::InvalidArgument(std::string("a ") + ShapeTypeName(s.shape) + " is always static (kinematic true)");
  }
  // kinematic bodies are infinite-mass like static ones; only their motion differs
  const bool is_static = s.fixed || s.kinematic || s.shape == ShapeType::kPlane || IsSurface(s.shape);
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
  b.x = s.position + q * com;
  b.frame_origin = Vec3::Zero() - com;  // +0, not -0, for a centred shape
  if (is_static) {
    b.MakeStatic();
    if (s.kinematic) b.motion = MotionType::kKinematic;
  } else if (s.inertia) {
    b.SetMassProperties(*s.mass, *s.inertia);
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
