#include "service/physics/rigid_body.h"

#include "service/physics/mass_properties.h"

namespace contactsim {

Mat3 RigidBody::InvInertiaWorld() const {
  const Mat3 R = Rotation();
  return R * inv_inertia_body * R.transpose();
}

Mat3 RigidBody::InertiaWorld() const {
  const Mat3 R = Rotation();
  return R * inertia_body * R.transpose();
}

Vec3 RigidBody::LinearVelocity() const {
  if (motion == MotionType::kKinematic) return kinematic_v;
  return P * inv_mass;
}

Vec3 RigidBody::AngularVelocity() const {
  if (motion == MotionType::kKinematic) return kinematic_w;
  if (motion == MotionType::kStatic) return Vec3::Zero();
  return InvInertiaWorld() * L;
}

Vec3 RigidBody::PointVelocity(const Vec3& p_W) const {
  return LinearVelocity() + AngularVelocity().cross(p_W - x);
}

void RigidBody::SetVelocity(const Vec3& v, const Vec3& w) {
  switch (motion) {
    case MotionType::kDynamic:
      P = mass * v;
      L = InertiaWorld() * w;
      break;
    case MotionType::kKinematic:
      kinematic_v = v;
      kinematic_w = w;
      break;
    case MotionType::kStatic: break;
  }
}

void RigidBody::ApplyImpulse(const Vec3& J, const Vec3& p_W) {
  if (!IsDynamic()) return;
  P += J;
  L += (p_W - x).cross(J);
}

void RigidBody::ApplyAngularImpulse(const Vec3& H) {
  if (!IsDynamic()) return;
  L += H;
}

double RigidBody::KineticEnergy() const {
  if (!IsDynamic()) return 0.0;
  // T = |P|^2 / 2m + L . w / 2
  return 0.5 * P.squaredNorm() * inv_mass + 0.5 * L.dot(AngularVelocity());
}

void RigidBody::SetMassFromDensity(double density) {
  const MassProperties mp = ComputeMassProperties(shape, density);
  SetMass(mp.mass);
}

void RigidBody::SetMass(double new_mass) {
  if (explicit_inertia && mass > 0.0) {
    // the given distribution of mass keeps its shape: I scales with m
    SetMassProperties(new_mass, inertia_body * (new_mass / mass));
    return;
  }
  // Inertia scales with mass for a fixed shape: take the unit-density tensor
  // about the body origin (a compound's children are posed about it).
  const Vec3 v = LinearVelocity();
  const Vec3 w = AngularVelocity();
  const MassProperties unit = ComputeMassProperties(shape, 1.0);
  motion = MotionType::kDynamic;
  mass = new_mass;
  inv_mass = 1.0 / new_mass;
  inertia_body = InertiaAboutOrigin(unit) * (new_mass / unit.mass);
  inv_inertia_body = inertia_body.inverse();
  SetVelocity(v, w);
}

void RigidBody::SetMassProperties(double new_mass, const Mat3& inertia) {
  const Vec3 v = LinearVelocity();
  const Vec3 w = AngularVelocity();
  motion = MotionType::kDynamic;
  mass = new_mass;
  inv_mass = 1.0 / new_mass;
  inertia_body = 0.5 * (inertia + inertia.transpose());
  inv_inertia_body = inertia_body.inverse();
  explicit_inertia = true;
  SetVelocity(v, w);
}

void RigidBody::MakeStatic() {
  motion = MotionType::kStatic;
  mass = 0.0;
  inv_mass = 0.0;
  inertia_body.setZero();
  inv_inertia_body.setZero();
  P.setZero();
  L.setZero();
}

}  // namespace contactsim
