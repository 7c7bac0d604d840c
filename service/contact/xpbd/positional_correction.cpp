#include "service/contact/xpbd/positional_correction.h"

namespace contactsim {

double GeneralizedInverseMass(const RigidBody& body, const Vec3& r, const Vec3& n) {
  if (!body.IsDynamic()) return 0.0;
  const Vec3 rn = r.cross(n);
  return body.inv_mass + rn.dot(body.InvInertiaWorld() * rn);
}

void ApplyPositionalImpulse(RigidBody& body, const Vec3& p, const Vec3& r) {
  if (!body.IsDynamic()) return;
  body.x += p * body.inv_mass;
  ApplyAngularPositionalImpulse(body, r.cross(p));
}

void ApplyAngularPositionalImpulse(RigidBody& body, const Vec3& h) {
  if (!body.IsDynamic()) return;
  const Vec3 phi = body.InvInertiaWorld() * h;
  // q += 1/2 [phi, 0] q, then renormalised (eq. 8)
  const Quat dq = Quat(0.0, phi.x(), phi.y(), phi.z()) * body.q;
  body.q.coeffs() += 0.5 * dq.coeffs();
  body.q.normalize();
}

double SolvePositionalConstraint(RigidBody& a, const Vec3& ra, RigidBody& b, const Vec3& rb, const Vec3& n,
                                 double c, double alpha_tilde, double* lambda) {
  const double w = GeneralizedInverseMass(a, ra, n) + GeneralizedInverseMass(b, rb, n) + alpha_tilde;
  if (w <= 0.0) return 0.0;
  const double dlambda = (c - alpha_tilde * *lambda) / w;
  *lambda += dlambda;
  const Vec3 p = dlambda * n;
  ApplyPositionalImpulse(b, p, rb);
  ApplyPositionalImpulse(a, -p, ra);
  return dlambda;
}

double SolveAngularConstraint(RigidBody& a, RigidBody& b, const Vec3& n, double c, double alpha_tilde,
                              double* lambda) {
  const double wa = a.IsDynamic() ? n.dot(a.InvInertiaWorld() * n) : 0.0;
  const double wb = b.IsDynamic() ? n.dot(b.InvInertiaWorld() * n) : 0.0;
  const double w = wa + wb + alpha_tilde;
  if (w <= 0.0) return 0.0;
  const double dlambda = (c - alpha_tilde * *lambda) / w;
  *lambda += dlambda;
  ApplyAngularPositionalImpulse(b, dlambda * n);
  ApplyAngularPositionalImpulse(a, -dlambda * n);
  return dlambda;
}

}  // namespace contactsim
