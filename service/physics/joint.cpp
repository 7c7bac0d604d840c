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
  }
  return "?";
}

bool ParseJointKind(const std::string& name, JointKind* kind) {
  for (JointKind k : {JointKind::kDistance, JointKind::kBall, JointKind::kHinge, JointKind::kFixed}) {
    if (name == JointKindName(k)) {
      *kind = k;
      return true;
    }
  }
  return false;
}

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

Status CheckJointSettings(const JointSettings& s) {
  const char* kind = JointKindName(s.kind);
  const bool hinge = s.kind == JointKind::kHinge;
  if (s.body_a == kWorldBody) return Status::InvalidArgument("body_a must be a body id, got 0 (the world)");
  if (s.body_b == s.body_a) {
    return Status::InvalidArgument("body_b must differ from body_a: a body cannot be jointed to itself (id " +
                                   std::to_string(s.body_a) + ")");
  }
  Status st = CheckFinite("anchor", s.anchor);
  if (!st.ok()) return st;
  if (s.axis && !hinge) return Status::InvalidArgument(std::string("axis applies to hinge joints only, not ") + kind);
  if (s.limits && !hinge) return Status::InvalidArgument(std::string("limits apply to hinge joints only, not ") + kind);
  if (s.length && s.kind != JointKind::kDistance) {
    return Status::InvalidArgument(std::string("length applies to distance joints only, not ") + kind);
  }
  if (hinge) {
    if (!s.axis) return Status::InvalidArgument("axis is required for a hinge joint");
    if (!s.axis->allFinite() || s.axis->norm() < 1e-9) {
      return Status::InvalidArgument("axis must be a finite nonzero vector, got " + FormatValue(*s.axis));
    }
  }
  if (s.length && !(st = CheckPositive("length", *s.length)).ok()) return st;
  if (s.limits) {
    const auto [lower, upper] = *s.limits;
    if (!(st = CheckInRange("limits.lower", lower, -kPi, kPi)).ok()) return st;
    if (!(st = CheckInRange("limits.upper", upper, -kPi, kPi)).ok()) return st;
    if (lower > upper) {
      return Status::InvalidArgument("limits must have lower <= upper, got lower " + FormatValue(lower) +
                                     " > upper " + FormatValue(upper));
    }
  }
  return Status::Ok();
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
  *joint = j;
  return Status::Ok();
}

double HingeAngle(const Joint& joint, const RigidBody& a, const RigidBody* b) {
  // q_B = q_A q_twist rest, with q_twist a rotation about axis_a (A's frame)
  Quat twist = a.q.conjugate() * BodyOrientation(b) * joint.rest.conjugate();
  if (twist.w() < 0.0) twist.coeffs() = -twist.coeffs();  // same rotation, angle within [-pi, pi]
  return 2.0 * portable::Atan2(twist.vec().dot(joint.axis_a), twist.w());
}

}  // namespace contactsim
