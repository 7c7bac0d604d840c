#include "service/contact/soft/wide/soft_wide_bodies.h"

#include <cmath>

#include "service/physics/math.h"

namespace contactsim {
namespace {

// bodies a thread loads or stores at a time
constexpr int kWideBodyGrain = 256;

using Vec3f = Eigen::Vector3f;
using Mat3f = Eigen::Matrix3f;

void LoadWideBody(const RigidBody& b, const SoftBody& s, WideBody* state, WideBodyMotion* m) {
  *state = WideBody{};
  Eigen::Map<Vec3f>(state->v) = s.v.cast<float>();
  Eigen::Map<Vec3f>(state->w) = s.w.cast<float>();
  *m = WideBodyMotion{};
  m->inv_mass = static_cast<float>(s.inv_mass);
  m->inv_inertia = s.inv_inertia.cast<float>();
  m->substepped = s.substepped;
  if (s.inv_mass == 0.0) return;
  m->accel = (s.inv_mass * b.force).cast<float>();
  m->torque = b.torque.cast<float>();
  m->hold_momentum = !s.isotropic;
  m->R0 = s.R0t.transpose().cast<float>();
  m->inertia_body = b.inertia_body.cast<float>();
  m->inv_inertia_body = b.inv_inertia_body.cast<float>();
}

// exp(phi) as QuatFromRotationVector (math.h), whose sine and cosine are
// portable_math.h's, so the float path's turns are the same on every build
Eigen::Quaternionf TurnOf(const Vec3f& phi) { return QuatFromRotationVector(phi.cast<double>()).cast<float>(); }

// R(q) - I, column-major, from Eigen's toRotationMatrix's products without
// its 1 - ...: the diagonal keeps its digits at a small turn
void TurnMinusIdentity(const Eigen::Quaternionf& q, float* m) {
  const float tx = 2.0f * q.x(), ty = 2.0f * q.y(), tz = 2.0f * q.z();
  const float twx = tx * q.w(), twy = ty * q.w(), twz = tz * q.w();
  const float txx = tx * q.x(), txy = ty * q.x(), txz = tz * q.x();
  const float tyy = ty * q.y(), tyz = tz * q.y(), tzz = tz * q.z();
  const float columns[9] = {-(tyy + tzz), txy + twz,    txz - twy,  // column 0
                            txy - twz,    -(txx + tzz), tyz + twx,  // column 1
                            txz + twy,    tyz - twx,    -(txx + tyy)};
  for (int k = 0; k < 9; ++k) m[k] = columns[k];
}

}  // namespace

void LoadWideBodies(const World& world, const std::vector<SoftBody>& soft, ParallelRunner& runner,
                    WideBodies* bodies) {
  const int n = static_cast<int>(soft.size());
  bodies->state.resize(n + 1);
  bodies->motion.resize(n + 1);
  bodies->state[n] = WideBody{};
  bodies->motion[n] = WideBodyMotion{};
  runner.For(n, kWideBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      LoadWideBody(world.bodies()[i], soft[i], &bodies->state[i], &bodies->motion[i]);
    }
  });
}

void IntegrateWideVelocities(float h, int begin, int end, WideBodies& bodies) {
  for (int i = begin; i < end; ++i) {
    const WideBodyMotion& m = bodies.motion[i];
    if (!m.substepped || m.inv_mass == 0.0f) continue;
    WideBody& s = bodies.state[i];
    Eigen::Map<Vec3f>(s.v) += h * m.accel;
    Eigen::Map<Vec3f>(s.w) += h * (m.inv_inertia * m.torque);
  }
}

void IntegrateWidePositions(float h, int begin, int end, WideBodies& bodies) {
  for (int i = begin; i < end; ++i) {
    WideBodyMotion& m = bodies.motion[i];
    if (!m.substepped) continue;
    WideBody& s = bodies.state[i];
    Eigen::Map<Vec3f> w(s.w);
    // L = I_old w, held across the turn; then w = I_new^-1 L
    Vec3f L = Vec3f::Zero();
    if (m.hold_momentum) {
      const Mat3f R_old = m.dq.toRotationMatrix() * m.R0;
      L = R_old * (m.inertia_body * (R_old.transpose() * w));
    }
    Eigen::Map<Vec3f>(s.dp) += h * Eigen::Map<const Vec3f>(s.v);
    m.dq = (TurnOf(h * w) * m.dq).normalized();
    TurnMinusIdentity(m.dq, s.turn);
    if (!m.hold_momentum) continue;
    const Mat3f R = (Eigen::Map<const Mat3f>(s.turn) + Mat3f::Identity()) * m.R0;
    m.inv_inertia = R * m.inv_inertia_body * R.transpose();
    w = m.inv_inertia * L;
  }
}

void StoreWideBodies(const WideBodies& bodies, ParallelRunner& runner, std::vector<SoftBody>& soft, World& world) {
  runner.For(static_cast<int>(soft.size()), kWideBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      const WideBodyMotion& m = bodies.motion[i];
      if (!m.substepped) continue;
      const WideBody& f = bodies.state[i];
      SoftBody& s = soft[i];
      s.v = Eigen::Map<const Vec3f>(f.v).cast<double>();
      s.w = Eigen::Map<const Vec3f>(f.w).cast<double>();
      s.dp = Eigen::Map<const Vec3f>(f.dp).cast<double>();
      const Quat dq = m.dq.cast<double>();
      s.dR = dq.toRotationMatrix();
      RigidBody& b = world.bodies()[i];
      b.x = s.x0 + s.dp;
      b.q = (dq * s.q0).normalized();
    }
  });
}

}  // namespace contactsim
