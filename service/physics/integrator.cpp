#include "service/physics/integrator.h"

#include <Eigen/LU>
#include <algorithm>

namespace contactsim {
namespace {

// Rotation over h with the world angular momentum L held fixed: the implicit
// midpoint rule on Euler's equations in the body frame, L_b' = L_b x w_b,
//   L1 = cay(-h w^) L0,  w = I_b^-1 (L0 + L1) / 2,
// solved by fixed-point iteration. The midpoint rule conserves every
// quadratic invariant, here |L| and the kinetic energy L_b . I_b^-1 L_b / 2,
// so a torque-free body neither gains nor loses energy (an explicit update
// drifts by O(1) over 10^4 steps). The matching rotation is the body-frame
// increment cay(h w^), whose quaternion is (1, h w / 2) normalised.
void RotateWithFixedMomentum(RigidBody& b, double h) {
  const Vec3 L0 = b.q.conjugate() * b.L;
  const double scale = std::max(L0.norm(), 1e-300);
  Vec3 L1 = L0;
  Vec3 w = b.inv_inertia_body * L0;
  for (int it = 0; it < 50; ++it) {
    w = b.inv_inertia_body * (0.5 * (L0 + L1));
    const Mat3 half = 0.5 * h * Skew(w);
    const Vec3 next = (Mat3::Identity() + half).partialPivLu().solve((Mat3::Identity() - half) * L0);
    const double change = (next - L1).norm();
    L1 = next;
    if (change <= 1e-15 * scale) break;
  }
  w = b.inv_inertia_body * (0.5 * (L0 + L1));
  const Vec3 half_angle = 0.5 * h * w;
  b.q = (b.q * Quat(1.0, half_angle.x(), half_angle.y(), half_angle.z()).normalized()).normalized();
}

void Rotate(RigidBody& b, double h) {
  if (b.IsDynamic()) {
    RotateWithFixedMomentum(b, h);
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
  for (RigidBody& b : world.bodies()) {
    if (b.motion == MotionType::kStatic) continue;
    b.x += b.LinearVelocity() * dt;
    Rotate(b, dt);
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
  Rotate(b, h);
}

}  // namespace contactsim
