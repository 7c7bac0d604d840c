#include "service/contact/soft/soft_bodies.h"

namespace contactsim {

void LoadSoftBodies(const World& world, const std::vector<char>& substepped, std::vector<SoftBody>* bodies) {
  const auto& src = world.bodies();
  bodies->resize(src.size());
  for (size_t i = 0; i < src.size(); ++i) {
    const RigidBody& b = src[i];
    SoftBody& s = (*bodies)[i];
    s.v = b.LinearVelocity();
    s.w = b.AngularVelocity();
    s.inv_mass = b.IsDynamic() ? b.inv_mass : 0.0;
    s.inv_inertia = b.IsDynamic() ? b.InvInertiaWorld() : Mat3::Zero();
    s.x0 = b.x;
    s.q0 = b.q;
    s.R0t = b.q.toRotationMatrix().transpose();
    const Mat3& I = b.inertia_body;
    s.isotropic = I.isDiagonal() && I(0, 0) == I(1, 1) && I(1, 1) == I(2, 2);
    s.dp.setZero();
    s.dR.setIdentity();
    s.substepped = substepped[i] != 0 && b.motion != MotionType::kStatic;
  }
}

void IntegrateSoftVelocities(const World& world, double h, std::vector<SoftBody>& bodies) {
  const auto& src = world.bodies();
  for (size_t i = 0; i < bodies.size(); ++i) {
    SoftBody& s = bodies[i];
    if (!s.substepped || s.inv_mass == 0.0) continue;
    s.v += h * s.inv_mass * src[i].force;
    s.w += h * (s.inv_inertia * src[i].torque);
  }
}

void IntegrateSoftPositions(double h, World& world, std::vector<SoftBody>& bodies, bool track_motion) {
  auto& dst = world.bodies();
  for (size_t i = 0; i < bodies.size(); ++i) {
    SoftBody& s = bodies[i];
    if (!s.substepped) continue;
    RigidBody& b = dst[i];
    const bool hold_momentum = s.inv_mass != 0.0 && !s.isotropic;
    // L = I_old w, held across the turn; then w = I_new^-1 L
    Vec3 L = Vec3::Zero();
    if (hold_momentum) {
      const Mat3 R_old = b.q.toRotationMatrix();
      L = R_old * (b.inertia_body * (R_old.transpose() * s.w));
    }
    b.x += h * s.v;
    b.q = (QuatFromRotationVector(h * s.w) * b.q).normalized();
    if (!track_motion && !hold_momentum) continue;
    const Mat3 R = b.q.toRotationMatrix();
    if (track_motion) {
      s.dp = b.x - s.x0;
      s.dR = R * s.R0t;
    }
    if (!hold_momentum) continue;
    s.inv_inertia = R * b.inv_inertia_body * R.transpose();
    s.w = s.inv_inertia * L;
  }
}

void StoreSoftBodies(const std::vector<SoftBody>& bodies, World& world) {
  auto& dst = world.bodies();
  for (size_t i = 0; i < bodies.size(); ++i) {
    const SoftBody& s = bodies[i];
    if (!s.substepped || s.inv_mass == 0.0) continue;
    RigidBody& b = dst[i];
    b.P = b.mass * s.v;
    b.L = b.InertiaWorld() * s.w;
  }
}

}  // namespace contactsim
