#include "service/contact/xpbd/xpbd_joints.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "service/contact/xpbd/positional_correction.h"
#include "service/contact/xpbd/xpbd_slider.h"
#include "service/physics/portable_math.h"

namespace contactsim {
namespace {

// Turns B relative to A by the rotation vector `rotation` (rad, world).
void Turn(RigidBody& a, RigidBody& b, const Vec3& rotation, double alpha_tilde, double* lambda) {
  const double angle = rotation.norm();
  if (angle <= 0.0) return;
  SolveAngularConstraint(a, b, rotation / angle, angle, alpha_tilde, lambda);
}

// Moves B's anchor pb towards A's anchor pa so that their distance becomes `length`.
void Attach(RigidBody& a, RigidBody& b, const Joint& j, double length, double alpha_tilde, double* lambda) {
  const Vec3 pa = AnchorWorld(j.anchor_a, &a);
  const Vec3 pb = AnchorWorld(j.anchor_b, &b);
  const Vec3 d = pa - pb;
  const double distance = d.norm();
  if (distance <= 0.0) return;  // met exactly (a ball joint at rest), or no direction (distance: length > 0)
  SolvePositionalConstraint(a, pa - a.x, b, pb - b.x, d / distance, distance - length, alpha_tilde, lambda);
}

void SolveJoint(const Joint& j, RigidBody& a, RigidBody& b, double alpha_tilde, XpbdJointLambda& lambda) {
  if (j.kind == JointKind::kHinge) {
    const Vec3 axis_a = a.q * j.axis_a;
    const Vec3 cross = (b.q * j.axis_b).cross(axis_a);
    const double s = cross.norm();
    if (s > 0.0) Turn(a, b, cross / s * portable::Asin(std::min(1.0, s)), alpha_tilde, &lambda[0]);
    if (j.limited) {
      const double angle = HingeAngle(j, a, &b);
      const double excess = angle < j.lower ? j.lower - angle : angle > j.upper ? j.upper - angle : 0.0;
      if (excess != 0.0) Turn(a, b, (a.q * j.axis_a) * excess, alpha_tilde, &lambda[1]);
    }
  } else if (j.kind == JointKind::kFixed || j.kind == JointKind::kPrismatic) {
    Quat e = a.q * j.rest * b.q.conjugate();
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const double s = e.vec().norm();
    if (s > 0.0) Turn(a, b, e.vec() / s * (2.0 * portable::Atan2(s, e.w())), alpha_tilde, &lambda[0]);
  }
  if (j.kind == JointKind::kPrismatic) return SolveXpbdSlide(j, a, b, alpha_tilde, lambda);
  Attach(a, b, j, j.kind == JointKind::kDistance ? j.length : 0.0, alpha_tilde, &lambda[2]);
}

}  // namespace

void SolveXpbdJoints(World& world, double alpha_tilde, std::vector<XpbdJointLambda>* lambdas) {
  // the world as a static body at the origin: AnchorWorld(p, &ground) = p
  RigidBody ground;
  ground.motion = MotionType::kStatic;
  ground.x.setZero();
  ground.q.setIdentity();
  auto& bodies = world.bodies();
  const auto& joints = world.joints();
  for (size_t k = 0; k < joints.size(); ++k) {
    const Joint& j = joints[k];
    RigidBody& a = bodies[world.IndexOf(j.body_a)];
    RigidBody& b = j.body_b == kWorldBody ? ground : bodies[world.IndexOf(j.body_b)];
    if (!a.IsDynamic() && !b.IsDynamic()) continue;
    SolveJoint(j, a, b, alpha_tilde, (*lambdas)[k]);
  }
}

}  // namespace contactsim
