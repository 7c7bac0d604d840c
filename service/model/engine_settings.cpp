#include "service/model/engine_settings.h"

#include <cmath>

#include "service/physics/cylinder_hull.h"
#include "service/physics/hull_memo.h"
#include "service/physics/validation.h"

namespace contactsim::model {
namespace {


Eigen::Vector4d Wxyz(const Quat& q) { return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()); }

// One collision element as a part of the body's compound shape, in the
// owner link's frame: a cylinder as the convex hull of two regular
// polygons (cylinder_hull.h), a mesh as the hull of its vertices, at most
// `max_hull_vertices` of them (hull_vertex_budget.h; 0: all). A mesh with
// no hull keeps its vertices, so that building the shape names the part
// and the reason, as for any other hull.
ShapePart PartOf(const PartPlan& part, int max_hull_vertices, HullMemo* memo) {
  const Geometry& g = *part.geometry;
  ShapePart p;
  p.position = part.origin.position;
  p.orientation = part.origin.orientation;
  switch (g.type) {
    case GeometryType::kBox: p.type = ShapeType::kBox; p.half_extents = 0.5 * g.box_size; break;
    case GeometryType::kSphere: p.type = ShapeType::kSphere; p.radius = g.radius; break;
    case GeometryType::kCapsule:
      p.type = ShapeType::kCapsule;
      p.radius = g.radius;
      p.half_length = 0.5 * g.length;
      break;
    case GeometryType::kCylinder:
      p.type = ShapeType::kConvex;
      p.points = CylinderPoints(g.radius, g.length, CylinderSides());
      break;
    case GeometryType::kMesh:
      p.type = ShapeType::kConvex;
      if (!memo->BudgetedPoints(g.mesh_vertices, max_hull_vertices, &p.points).ok()) p.points = g.mesh_vertices;
      break;
  }
  return p;
}

}  // namespace

Status MakeBodySettings(const BodyPlan& plan, const Pose& owner_W, bool is_static, int max_hull_vertices,
                        const std::string& where, HullMemo* memo, BodySettings* settings) {
  if (plan.parts.empty()) {
    return Status::InvalidArgument(where + " has no collision element (with the links merged into it); a body "
                                   "needs at least one shape");
  }
  if (plan.parts.size() > static_cast<size_t>(kMaxShapeParts)) {
    return Status::InvalidArgument(where + " has " + std::to_string(plan.parts.size()) +
                                   " collision elements (with the links merged into it); a body takes at most " +
                                   std::to_string(kMaxShapeParts));
  }
  BodySettings s;
  s.shape = ShapeType::kCompound;
  for (const PartPlan& part : plan.parts) s.parts.push_back(PartOf(part, max_hull_vertices, memo));
  s.position = owner_W.position;
  s.orientation = Wxyz(owner_W.orientation);
  s.fixed = is_static;
  if (!is_static) {
    // the file's mass properties exactly, or PyBullet's default for a body without any
    s.mass = plan.has_mass ? plan.mass : kDefaultLinkMass;
    s.center_of_mass = plan.has_mass ? plan.com : Vec3::Zero();
    s.inertia = plan.has_mass ? plan.inertia : Mat3(kDefaultLinkInertia * Mat3::Identity());
  }
  *settings = std::move(s);
  return Status::Ok();
}

JointActuator MakeJointActuator(const ModelJoint& j) {
  JointActuator a;
  if (!j.limits) return a;
  if (j.limits->effort > 0.0) a.effort_limit = j.limits->effort;
  if (j.limits->velocity > 0.0) a.velocity_limit = j.limits->velocity;
  return a;
}

Status MakeJointSettings(const ModelJoint& j, const Pose& child_W, const std::string& where, JointSettings* settings) {
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
      s.kind = JointKind::kPrismatic;
      s.axis = axis_W;
      if (j.limits) s.limits = std::make_pair(j.limits->lower, j.limits->upper);
      break;
    case JointType::kPlanar:
      return Status::InvalidArgument(where + " is planar; contactsim has no planar joint");
    case JointType::kFixed:
    case JointType::kFloating:
      return Status::Internal(where + ": a fixed or floating joint adds no joint row");
  }
  s.damping = j.damping;
  s.friction = j.friction;
  *settings = std::move(s);
  return Status::Ok();
}

Status ApplySelfCollision(bool self_collide, int group, BodySettings* settings) {
  // links joined by a joint never collide (collide_connected is false)
  if (!self_collide) settings->collision_group = group;
  return Status::Ok();
}

}  // namespace contactsim::model
