#include "service/physics/integrator.h"

namespace contactsim {

void IntegrateMomenta(World& world, double dt) {
  for (RigidBody& b : world.bodies()) {
    if (!b.IsDynamic()) continue;
    // dP/dt = F, dL/dt = tau (Witkin and Baraff). Holding L rather than w
    // as state keeps a torque-free body's angular momentum exactly constant;
    // the gyroscopic term w x I w is implicit in w = I(q)^-1 L.
    b.P += b.force * dt;
    b.L += b.torque * dt;
  }
}

void IntegratePositions(World& world, double dt) {
  for (RigidBody& b : world.bodies()) {
    if (b.motion == MotionType::kStatic) continue;
    b.x += b.LinearVelocity() * dt;
    // q <- exp(w dt / 2) q: the exact rotation for constant w over the step,
    // so the quaternion stays unit up to round-off; renormalise for that.
    b.q = (QuatFromRotationVector(b.AngularVelocity() * dt) * b.q).normalized();
  }
}

void AdvanceBallistic(RigidBody& b, double h) {
  switch (b.motion) {
    case MotionType::kStatic: return;
    case MotionType::kKinematic:
      b.x += b.kinematic_v * h;
      break;
    case MotionType::kDynamic:
      b.x += (b.LinearVelocity() + 0.5 * h * b.inv_mass * b.force) * h;
      b.P += b.force * h;
      b.L += b.torque * h;
      break;
  }
  b.q = (QuatFromRotationVector(b.AngularVelocity() * h) * b.q).normalized();
}

}  // namespace contactsim
