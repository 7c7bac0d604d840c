#include "service/contact/barrier/affine_prediction.h"

#include <algorithm>

#include "service/physics/integrator.h"

namespace contactsim {

Vec12 PredictAffine(const RigidBody& body, const Vec12& q, const Vec12& qdot, double h) {
  const Vec3 p = AffinePosition(q) + h * qdot.head<3>() + (h * h * body.inv_mass) * body.force;
  const Quat rotation = MidpointRotation(body.q, body.L + h * body.torque, body.inv_inertia_body, h);
  return AffineFromPose(p, rotation.toRotationMatrix());
}

Vec3 EndAngularMomentum(const RigidBody& body, const Quat& q0, const Quat& q1, double h) {
  Quat increment = q0.conjugate() * q1;
  // q and -q are one rotation; the midpoint rule's increment has w > 0
  if (increment.w() < 0.0) increment.coeffs() = -increment.coeffs();
  // (a half turn in one step has no Cayley angle; 1e-9 keeps w finite)
  const Vec3 w = (2.0 / (h * std::max(increment.w(), 1e-9))) * increment.vec();
  const Vec3 Iw = body.inertia_body * w;
  return q1 * (Iw - 0.5 * h * w.cross(Iw));
}

}  // namespace contactsim
