// Bounds on how far bodies can move towards each other, for methods that
// look ahead over a step: conservative advancement in time-of-impact
// searches (Mirtich 1996 thesis, ch. 2) and speculative contact margins.
#pragma once

#include "service/physics/rigid_body.h"

namespace contactsim {

// Radius (m) of a sphere about the centre of mass that holds the shape; 0
// for planes (always static: no rotation sweeps them).
double BoundingRadius(const Shape& shape);

// Upper bound (m/s) on the rate at which the distance between a and b can
// shrink during the next h seconds: relative linear speed, plus what the
// accumulated forces add over h, plus each body's rotation sweeping its
// bounding sphere (|w| r).
double ClosingSpeedBound(const RigidBody& a, const RigidBody& b, double h);

// One body's terms of that bound, for a caller bounding many pairs: found
// once a body rather than once a pair (its angular velocity takes the
// world inverse inertia), the bound from them is the same number.
struct BodyMotion {
  Vec3 v = Vec3::Zero();      // m/s
  Vec3 accel = Vec3::Zero();  // m/s^2, F / m
  double spin_reach = 0.0;    // m/s, |w| times the bounding radius
};
BodyMotion MotionOf(const RigidBody& body);
double ClosingSpeedBound(const BodyMotion& a, const BodyMotion& b, double h);

}  // namespace contactsim
