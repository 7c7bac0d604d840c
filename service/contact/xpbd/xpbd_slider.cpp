#include "service/contact/xpbd/xpbd_slider.h"

#include "service/contact/xpbd/positional_correction.h"

namespace contactsim {

void SolveXpbdSlide(const Joint& j, RigidBody& a, RigidBody& b, double alpha_tilde, XpbdJointLambda& lambda) {
  const Vec3 axis = a.q * j.axis_a;
  Vec3 pa = AnchorWorld(j.anchor_a, &a);
  Vec3 pb = AnchorWorld(j.anchor_b, &b);
  const Vec3 d = pa - pb;
  const Vec3 across = d - d.dot(axis) * axis;
  const double off = across.norm();
  if (off > 0.0) SolvePositionalConstraint(a, pa - a.x, b, pb - b.x, across / off, off, alpha_tilde, &lambda[2]);
  if (!j.limited) return;
  pa = AnchorWorld(j.anchor_a, &a);
  pb = AnchorWorld(j.anchor_b, &b);
  const double slide = PrismaticSlide(j, a, &b);
  const double excess = slide < j.lower ? j.lower - slide : slide > j.upper ? j.upper - slide : 0.0;
  if (excess != 0.0) SolvePositionalConstraint(a, pa - a.x, b, pb - b.x, a.q * j.axis_a, excess, alpha_tilde, &lambda[1]);
}

}  // namespace contactsim
