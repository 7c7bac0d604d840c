// Mass, centre of mass and inertia of a shape of uniform density, and the
// checks on mass properties given explicitly (a robot link's inertial).
#pragma once

#include <string>

#include "service/physics/math.h"
#include "service/physics/shape.h"
#include "service/physics/status.h"

namespace contactsim {

struct MassProperties {
  double mass = 0.0;                 // kg
  Mat3 inertia = Mat3::Zero();       // kg m^2, about the centre of mass, body frame
  Vec3 center = Vec3::Zero();        // m, centre of mass in the shape frame (zero but for a compound)
};

// Inertia about a point p of a body whose inertia about its centre of mass
// c is I_c: the parallel-axis theorem (Steiner),
//   I_p = I_c + m (|d|^2 E - d d^T),  d = c - p.
Mat3 ShiftInertia(const Mat3& inertia_c, double mass, const Vec3& d);

// The inertia about the shape frame's origin (which is the body's centre of
// mass once a body is built): `mp.inertia` shifted by `mp.center`.
Mat3 InertiaAboutOrigin(const MassProperties& mp);

// Volume of a bounded shape (m^3); 0 for a plane.
double ShapeVolume(const Shape& shape);

// Mass properties for a uniform density (kg/m^3). The inertia is the closed
// form for spheres, boxes and capsules, and the polyhedral mass integrals
// (Mirtich 1996) for convex hulls. A compound sums its children: masses and
// first moments, and each child's inertia turned into the body axes
// (R I R^T) and shifted to the common centre of mass by the parallel-axis
// theorem. Children that overlap are counted twice, as PyBullet and Bullet's
// btCompoundShape do: the volume is the sum of the children's. Not defined
// for planes.
MassProperties ComputeMassProperties(const Shape& shape, double density);

// An inertia tensor given explicitly (kg m^2, about the centre of mass):
// finite, symmetric (to 1e-9 of its largest entry), positive definite, and
// its principal moments obey the triangle inequality I1 + I2 >= I3 (to 1e-9
// relative), which every real mass distribution does. The message names
// `field` and the values.
Status CheckInertiaTensor(const std::string& field, const Mat3& inertia);

}  // namespace contactsim
