// A rigid body in the classic state form of Witkin and Baraff (SIGGRAPH 1997
// course notes, "Rigid Body Dynamics"): Y = (x, q, P, L) with
//   x  position of the centre of mass (world),
//   q  orientation as a unit quaternion (R = R(q), body to world),
//   P  linear momentum  m v,
//   L  angular momentum I w, with I = R I_body R^T,
// and dY/dt = (v, w x R, F, tau). v, w and I^-1 are derived from the state.
#pragma once

#include <cstdint>
#include <string>

#include "service/physics/math.h"
#include "service/physics/shape.h"

namespace contactsim {

using BodyId = int64_t;

// The defaults are what every contact method simulates: barrier's implicit
// step is inelastic and refuses restitution > 0 (method_support.h), so a
// world of default bodies can be switched to any method. Bullet, Box2D, ODE
// and Jolt default restitution to 0 as well.
struct Material {
  double restitution = 0.0;  // unitless, [0, 1]
  double friction = 0.5;     // unitless Coulomb coefficient, >= 0
};

enum class MotionType {
  kDynamic,    // moves under forces and contacts
  kStatic,     // never moves; infinite mass
  kKinematic,  // moves with its set velocity; infinite mass for contacts
};

struct RigidBody {
  BodyId id = 0;
  std::string name;
  Shape shape;
  Material material;
  MotionType motion = MotionType::kDynamic;
  // Collision filter (collision_filter.h): the bits this body is, the bits
  // it touches, and Box2D's group (same positive: always, same negative: never).
  uint32_t collision_category = 1;
  uint32_t collision_mask = 0xFFFFFFFF;
  int32_t collision_group = 0;

  double mass = 0.0;                          // kg (0 for static and kinematic)
  double inv_mass = 0.0;                      // 1/kg
  Mat3 inertia_body = Mat3::Zero();           // kg m^2, body frame
  Mat3 inv_inertia_body = Mat3::Zero();       // 1/(kg m^2), body frame
  // The inertia was given explicitly (explicit_inertia in BodySettings), not
  // found from the shape: a new mass scales it instead of recomputing it.
  bool explicit_inertia = false;

  // The frame the body was described in (BodySettings::position and
  // orientation place it: a robot link's frame, a hull's points' frame)
  // is its origin here, in the body frame, whose origin is the centre of
  // mass; its axes are the body axes. The link frame's world pose is
  // (x + q * frame_origin, q).
  Vec3 frame_origin = Vec3::Zero();           // m, body frame

  Vec3 x = Vec3::Zero();                      // m, world
  Quat q = Quat::Identity();                  // body to world
  Vec3 P = Vec3::Zero();                      // kg m/s, world
  Vec3 L = Vec3::Zero();                      // kg m^2/s, world

  Vec3 force = Vec3::Zero();                  // N, accumulated for this step
  Vec3 torque = Vec3::Zero();                 // N m, accumulated for this step

  // kinematic bodies have no momentum; their velocity is kept here
  Vec3 kinematic_v = Vec3::Zero();
  Vec3 kinematic_w = Vec3::Zero();

  // Sleeping (docs/physics.md, "Sleeping"; dynamic bodies only): how long
  // the body has stayed below the sleep speeds, and the island it sleeps
  // with, named by the island's lowest body id (0 while awake). A sleeping
  // body keeps its pose, has P = L = 0 and is not stepped.
  double rest_time = 0.0;                     // s
  BodyId sleep_island = 0;
  bool asleep() const { return sleep_island != 0; }

  bool IsDynamic() const { return motion == MotionType::kDynamic; }
  Mat3 Rotation() const { return q.toRotationMatrix(); }
  // I^-1 = R I_body^-1 R^T (world frame)
  Mat3 InvInertiaWorld() const;
  Mat3 InertiaWorld() const;
  Vec3 LinearVelocity() const;                // m/s
  Vec3 AngularVelocity() const;               // rad/s, world
  // velocity of the material point at p_W: v + w x (p - x)
  Vec3 PointVelocity(const Vec3& p_W) const;
  void SetVelocity(const Vec3& v, const Vec3& w);
  // P += J, L += (p - x) x J; no effect on static and kinematic bodies
  void ApplyImpulse(const Vec3& J, const Vec3& p_W);
  void ApplyAngularImpulse(const Vec3& H);
  double KineticEnergy() const;               // J
  // Sets mass and inertia from the shape and a density (kg/m^3) or a mass
  // (kg), the inertia about the body origin (the centre of mass); with an
  // explicit inertia, that inertia scaled by the new mass. Dynamic bodies only.
  void SetMassFromDensity(double density);
  void SetMass(double mass);
  // Sets a mass (kg) and an inertia about the centre of mass in the body
  // axes (kg m^2, checked by CheckInertiaTensor), marking it explicit.
  void SetMassProperties(double mass, const Mat3& inertia);
  void MakeStatic();
};

}  // namespace contactsim
