#include "service/model/engine_settings.h"

#include <cmath>

#include "service/physics/validation.h"

namespace contactsim::model {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector4d Wxyz(const Quat& q) { return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()); }

// One collision element as the body's one shape. A cylinder and several
// elements on one link need compound bodies, which the engine does not have.
Status SingleShape(const BodyPlan& plan, const Pose& owner_W, const std::string& where, BodySettings* s) {
  if (plan.parts.size() != 1) {
    return Status::InvalidArgument(where + " has " + std::to_string(plan.parts.size()) +
                                   " collision elements (with the links merged into it); the engine takes one "
                                   "shape per body until compound bodies exist");
  }
  const PartPlan& part = plan.parts[0];
  const Geometry& g = *part.geometry;
  const Pose at = Compose(owner_W, part.origin);
  s->position = at.position;
  s->orientation = Wxyz(at.orientation);
  switch (g.type) {
    case GeometryType::kBox: s->shape = ShapeType::kBox; s->half_extents = 0.5 * g.box_size; return Status::Ok();
    case GeometryType::kSphere: s->shape = ShapeType::kSphere; s->radius = g.radius; return Status::Ok();
    case GeometryType::kCapsule:
      s->shape = ShapeType::kCapsule;
      s->radius = g.radius;
      s->half_length = 0.5 * g.length;
      return Status::Ok();
    case GeometryType::kMesh:
      s->shape = ShapeType::kConvex;
      s->points = g.mesh_vertices;  // the hull of the vertices, in the geometry frame
      return Status::Ok();
    case GeometryType::kCylinder: break;
  }
  return Status::InvalidArgument(part.where + " is a cylinder; the engine has no cylinder shape or hull yet");
}

// The engine sets a body's inertia from its shape and mass, with the shape's
// centroid as the centre of mass; a link whose file gives other mass
// properties needs explicit ones, which the engine does not take yet.
Status CheckShapeMassProperties(const BodyPlan& plan, const Pose& owner_W, const std::string& where,
                                const BodySettings& s) {
  RigidBody b;
  if (Status st = CreateBody(s, Material(), &b); !st.ok()) return Status::InvalidArgument(where + ": " + st.message());
  const Vec3 com_W = owner_W.position + owner_W.orientation * plan.com;
  const Mat3 R = (owner_W.orientation.toRotationMatrix() * b.Rotation().transpose());  // owner axes -> body axes
  const Mat3 I_body = R.transpose() * plan.inertia * R;
  const double scale = 1.0 + plan.inertia.cwiseAbs().maxCoeff();
  if ((b.x - com_W).norm() > 1e-9 || (I_body - b.inertia_body).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    return Status::InvalidArgument(where + ": its centre of mass " + FormatValue(plan.com) +
                                   " or inertia is not its shape's; the engine takes explicit mass properties "
                                   "only once compound bodies exist");
  }
  return Status::Ok();
}

}  // namespace

Status MakeBodySettings(const BodyPlan& plan, const Pose& owner_W, bool is_static, const std::string& where,
                        BodySettings* settings) {
  BodySettings s;
  if (Status st = SingleShape(plan, owner_W, where, &s); !st.ok()) return st;
  s.fixed = is_static;
  if (is_static) {
    *settings = std::move(s);
    return Status::Ok();
  }
  BodyPlan mass = plan;
  if (!plan.has_mass) {
    mass.mass = kDefaultLinkMass;
    mass.com = Vec3::Zero();
    mass.inertia = kDefaultLinkInertia * Mat3::Identity();
  }
  s.mass = mass.mass;
  if (Status st = CheckShapeMassProperties(mass, owner_W, where, s); !st.ok()) return st;
  *settings = std::move(s);
  return Status::Ok();
}

Status MakeJointSettings(const ModelJoint& j, const Pose& child_W, const std::string& where, JointSettings* settings) {
  if (j.damping != 0.0 || j.friction != 0.0) {
    return Status::InvalidArgument(where + " has damping " + FormatValue(j.damping) + " and friction " +
                                   FormatValue(j.friction) + "; the engine's joints have neither yet");
  }
  JointSettings s;
  s.anchor = child_W.position;
  const Vec3 axis_W = child_W.orientation * j.axis.normalized();
  switch (j.type) {
    case JointType::kRevolute:
    case JointType::kContinuous:
      s.kind = JointKind::kHinge;
      s.axis = axis_W;
      // the hinge angle lives in (-pi, pi]: a stop beyond it is clamped to
      // it, and a range that covers the whole turn is no stop at all
      if (j.type == JointType::kRevolute && j.limits && (j.limits->lower > -kPi || j.limits->upper < kPi)) {
        s.limits = std::make_pair(std::max(j.limits->lower, -kPi), std::min(j.limits->upper, kPi));
      }
      break;
    case JointType::kPrismatic:
      return Status::InvalidArgument(where + " is prismatic; the engine has no prismatic joint yet");
    case JointType::kPlanar:
      return Status::InvalidArgument(where + " is planar; contactsim has no planar joint");
    case JointType::kFixed:
    case JointType::kFloating:
      return Status::Internal(where + ": a fixed or floating joint adds no joint row");
  }
  *settings = std::move(s);
  return Status::Ok();
}

Status ApplySelfCollision(bool self_collide, int group, BodySettings* settings) {
  (void)group;
  (void)settings;
  // links joined by a joint never collide (collision_detector.h); the other
  // pairs of one model collide until the engine has collision groups
  (void)self_collide;
  return Status::Ok();
}

}  // namespace contactsim::model
