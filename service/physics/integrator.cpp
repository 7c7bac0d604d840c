#include "service/physics/integrator.h"

#include <algorithm>

#include "service/physics/lu3.h"

namespace contactsim {

// The implicit midpoint rule on Euler's equations in the body frame,
// L_b' = L_b x w_b, solved by fixed-point iteration; the rotation is the
// body-frame increment cay(h w^), whose quaternion is (1, h w / 2)
// normalised (integrator.h).
Quat MidpointRotation(const Quat& q, const Vec3& L_W, const Mat3& inv_inertia_body, double h) {
  const Vec3 L0 = q.conjugate() * L_W;
  const double scale = std::max(L0.norm(), 1e-300);
  Vec3 L1 = L0;
  Vec3 w = inv_inertia_body * L0;
  for (int it = 0; it < 50; ++it) {
    w = inv_inertia_body * (0.5 * (L0 + L1));
    const Mat3 half = 0.5 * h * Skew(w);
    const Vec3 next = SolveLu3(Mat3::Identity() + half, (Mat3::Identity() - half) * L0);  // Eigen's LU, bit for bit
    const double change = (next - L1).norm();
    L1 = next;
    if (change <= 1e-15 * scale) break;
  }
  w = inv_inertia_body * (0.5 * (L0 + L1));
  const Vec3 half_angle = 0.5 * h * w;
  return (q * Quat(1.0, half_angle.x(), half_angle.y(), half_angle.z()).normalized()).normalized();
}

namespace {

void Rotate(RigidBody& b, double h) {
  if (b.IsDynamic()) {
    b.q = MidpointRotation(b.q, b.L, b.inv_inertia_body, h);
  } else if (b.motion == MotionType::kKinematic) {
    b.q = (QuatFromRotationVector(b.kinematic_w * h) * b.q).normalized();
  }
}

}  // namespace

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
  for (RigidBody& b : world.bodies()) IntegratePosition(b, dt);
}

void IntegratePosition(RigidBody& b, double dt) {
  if (b.motion == MotionType::kStatic) return;
  b.x += b.LinearVelocity() * dt;
  Rotate(b, dt);
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
  Rotate(b, h);
}

}  // namespace contactsim
