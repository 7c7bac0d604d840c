#include "service/physics/joint.h"

#include <cmath>

#include "service/physics/portable_math.h"
#include "service/physics/validation.h"

namespace contactsim {

const char* JointKindName(JointKind kind) {
  switch (kind) {
    case JointKind::kDistance: return "distance";
    case JointKind::kBall: return "ball";
    case JointKind::kHinge: return "hinge";
    case JointKind::kFixed: return "fixed";
    case JointKind::kPrismatic: return "prismatic";
  }
  return "?";
}

bool ParseJointKind(const std::string& name, JointKind* kind) {
  for (JointKind k : {JointKind::kDistance, JointKind::kBall, JointKind::kHinge, JointKind::kFixed,
                      JointKind::kPrismatic}) {
    if (name == JointKindName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

bool HasJointCoordinate(JointKind kind) { return kind == JointKind::kHinge || kind == JointKind::kPrismatic; }

Vec3 AnchorWorld(const Vec3& local, const RigidBody* body) {
  return body == nullptr ? local : Vec3(body->q * local + body->x);
}

Quat BodyOrientation(const RigidBody* body) { return body == nullptr ? Quat::Identity() : body->q; }

namespace {

// p_W expressed in the frame of `body` (world: unchanged)
Vec3 ToBodyFrame(const Vec3& p_W, const RigidBody* body) {
  return body == nullptr ? p_W : Vec3(body->q.conjugate() * (p_W - body->x));
}

}  // namespace

namespace {

// limits: a hinge's within [-pi, pi] (the angle's range), a slider's finite
Status CheckLimits(JointKind kind, double lower, double upper) {
  Status st;
  if (kind == JointKind::kHinge) {
    if (!(st = CheckInRange("limits.lower", lower, -kPi, kPi)).ok()) return st;
    if (!(st = CheckInRange("limits.upper", upper, -kPi, kPi)).ok()) return st;
  } else {
    if (!(st = CheckFinite("limits.lower", lower)).ok()) return st;
    if (!(st = CheckFinite("limits.upper", upper)).ok()) return st;
  }
  if (lower > upper) {
    return Status::InvalidArgument("limits must have lower <= upper, got lower " + FormatValue(lower) +
                                   " > upper " + FormatValue(upper));
  }
  return Status::Ok();
}

// damping and friction: finite, >= 0, and nonzero only on a joint coordinate
Status CheckJointDynamics(const JointSettings& s) {
  Status st;
  if (!(st = CheckNonNegative("damping", s.damping)).ok()) return st;
  if (!(st = CheckNonNegative("friction", s.friction)).ok()) return st;
  if (HasJointCoordinate(s.kind)) return Status::Ok();
  const char* kind = JointKindName(s.kind);
  if (s.damping != 0.0) {
    return Status::InvalidArgument(std::string("damping applies to hinge and prismatic joints only, not ") + kind +
                                   " (got " + FormatValue(s.damping) + ")");
  }
  if (s.friction != 0.0) {
    return Status::InvalidArgument(std::string("friction applies to hinge and prismatic joints only, not ") + kind +
                                   " (got " + FormatValue(s.friction) + ")");
  }
  return Status::Ok();
}

}  // namespace

Status CheckJointSettings(const JointSettings& s) {
  const char* kind = JointKindName(s.kind);
  const bool coordinate = HasJointCoordinate(s.kind);
  if (s.body_a == kWorldBody) return Status::InvalidArgument("body_a must be a body id, got 0 (the world)");
  if (s.body_b == s.body_a) {
    return Status::InvalidArgument("body_b must differ from body_a: a body cannot be jointed to itself (id " +
                                   std::to_string(s.body_a) + ")");
  }
  Status st = CheckFinite("anchor", s.anchor);
  if (!st.ok()) return st;
  if (s.axis && !coordinate) {
    return Status::InvalidArgument(std::string("axis applies to hinge and prismatic joints only, not ") + kind);
  }
  if (s.limits && !coordinate) {
    return Status::InvalidArgument(std::string("limits apply to hinge and prismatic joints only, not ") + kind);
  }
  if (s.length && s.kind != JointKind::kDistance) {
    return Status::InvalidArgument(std::string("length applies to distance joints only, not ") + kind);
  }
  if (coordinate) {
    if (!s.axis) return Status::InvalidArgument(std::string("axis is required for a ") + kind + " joint");
    if (!s.axis->allFinite() || s.axis->norm() < 1e-9) {
      return Status::InvalidArgument("axis must be a finite nonzero vector, got " + FormatValue(*s.axis));
    }
  }
  if (s.length && !(st = CheckPositive("length", *s.length)).ok()) return st;
  if (s.limits && !(st = CheckLimits(s.kind, s.limits->first, s.limits->second)).ok()) return st;
  return CheckJointDynamics(s);
}

Status CreateJoint(const JointSettings& s, const RigidBody& a, const RigidBody* b, Joint* joint) {
  Status st = CheckJointSettings(s);
  if (!st.ok()) return st;
  if (!a.IsDynamic() && (b == nullptr || !b->IsDynamic())) {
    return Status::InvalidArgument("a joint needs at least one dynamic body; body_a " + std::to_string(a.id) +
                                   " and body_b " + std::to_string(b == nullptr ? kWorldBody : b->id) +
                                   " are static or kinematic");
  }
  Joint j;
  j.kind = s.kind;
  j.body_a = a.id;
  j.body_b = b == nullptr ? kWorldBody : b->id;
  j.collide_connected = s.collide_connected;
  // a distance joint holds A's centre of mass; the others the anchor on both
  j.anchor_a = s.kind == JointKind::kDistance ? Vec3::Zero() : ToBodyFrame(s.anchor, &a);
  j.anchor_b = ToBodyFrame(s.anchor, b);
  j.rest = a.q.conjugate() * BodyOrientation(b);
  if (s.kind == JointKind::kDistance) {
    j.length = s.length ? *s.length : (a.x - s.anchor).norm();
    if (j.length <= 1e-9) {
      return Status::InvalidArgument("length must be given when body_a's centre of mass is at the anchor " +
                                     FormatValue(s.anchor) + " (current distance " + FormatValue(j.length) + ")");
    }
  }
  if (s.axis) {
    const Vec3 axis_W = s.axis->normalized();
    j.axis_a = a.q.conjugate() * axis_W;
    j.axis_b = BodyOrientation(b).conjugate() * axis_W;
  }
  if (s.limits) {
    j.limited = true;
    j.lower = s.limits->first;
    j.upper = s.limits->second;
  }
  j.damping = s.damping;
  j.friction = s.friction;
  *joint = j;
  return Status::Ok();
}

double HingeAngle(const Joint& joint, const RigidBody& a, const RigidBody* b) {
  // q_B = q_A q_twist rest, with q_twist a rotation about axis_a (A's frame)
  Quat twist = a.q.conjugate() * BodyOrientation(b) * joint.rest.conjugate();
  if (twist.w() < 0.0) twist.coeffs() = -twist.coeffs();  // same rotation, angle within [-pi, pi]
  return 2.0 * portable::Atan2(twist.vec().dot(joint.axis_a), twist.w());
}

double PrismaticSlide(const Joint& joint, const RigidBody& a, const RigidBody* b) {
  const Vec3 axis_W = a.q * joint.axis_a;
  return axis_W.dot(AnchorWorld(joint.anchor_b, b) - AnchorWorld(joint.anchor_a, &a));
}

double JointPosition(const Joint& joint, const RigidBody& a, const RigidBody* b) {
  switch (joint.kind) {
    case JointKind::kHinge: return HingeAngle(joint, a, b);
    case JointKind::kPrismatic: return PrismaticSlide(joint, a, b);
    default: return 0.0;
  }
}

double JointVelocity(const Joint& joint, const RigidBody& a, const RigidBody* b) {
  const Vec3 axis_W = a.q * joint.axis_a;
  const Vec3 w_a = a.AngularVelocity();
  const Vec3 w_b = b == nullptr ? Vec3::Zero() : b->AngularVelocity();
  if (joint.kind == JointKind::kHinge) return axis_W.dot(w_b - w_a);
  if (joint.kind != JointKind::kPrismatic) return 0.0;
  const Vec3 p_a = AnchorWorld(joint.anchor_a, &a);
  const Vec3 p_b = AnchorWorld(joint.anchor_b, b);
  const Vec3 pdot_b = b == nullptr ? Vec3::Zero() : b->PointVelocity(p_b);
  return axis_W.dot(pdot_b - a.PointVelocity(p_a)) + w_a.cross(axis_W).dot(p_b - p_a);
}

}  // namespace contactsim
