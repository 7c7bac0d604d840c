#include "service/contact/soft/soft_bodies.h"

namespace contactsim {
namespace {

// bodies a thread loads or stores at a time
constexpr int kSoftBodyGrain = 256;

}  // namespace

void LoadSoftBodies(const World& world, const std::vector<char>& substepped, ParallelRunner& runner,
                    std::vector<SoftBody>* bodies) {
  bodies->resize(world.bodies().size());
  runner.For(static_cast<int>(bodies->size()), kSoftBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) LoadSoftBody(world.bodies()[i], substepped[i] != 0, &(*bodies)[i]);
  });
}

void LoadSoftBody(const RigidBody& b, bool substepped, SoftBody* soft) {
  SoftBody& s = *soft;
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
  s.substepped = substepped && b.motion != MotionType::kStatic;
}

void IntegrateSoftVelocities(const World& world, double h, int begin, int end, std::vector<SoftBody>& bodies,
                             const std::vector<int>* order) {
  const auto& src = world.bodies();
  for (int q = begin; q < end; ++q) {
    const int i = order != nullptr ? (*order)[q] : q;
    SoftBody& s = bodies[i];
    if (!s.substepped || s.inv_mass == 0.0) continue;
    s.v += h * s.inv_mass * src[i].force;
    s.w += h * (s.inv_inertia * src[i].torque);
  }
}

void IntegrateSoftPositions(double h, int begin, int end, World& world, std::vector<SoftBody>& bodies,
                            bool track_motion, const std::vector<int>* order) {
  auto& dst = world.bodies();
  for (int q = begin; q < end; ++q) {
    const int i = order != nullptr ? (*order)[q] : q;
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

void StoreSoftBodies(const std::vector<SoftBody>& bodies, ParallelRunner& runner, World& world) {
  auto& dst = world.bodies();
  runner.For(static_cast<int>(bodies.size()), kSoftBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      const SoftBody& s = bodies[i];
      if (!s.substepped || s.inv_mass == 0.0) continue;
      RigidBody& b = dst[i];
      b.P = b.mass * s.v;
      b.L = b.InertiaWorld() * s.w;
    }
  });
}

}  // namespace contactsim
