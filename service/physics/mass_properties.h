// Mass, centre of mass and inertia of a shape of uniform density.
#pragma once

#include "service/physics/math.h"
#include "service/physics/shape.h"
#include "service/physics/status.h"

namespace contactsim {

struct MassProperties {
  double mass = 0.0;                 // kg
  Mat3 inertia = Mat3::Zero();       // kg m^2, about the centre of mass, body frame
};

// Volume of a bounded shape (m^3); 0 for a plane.
double ShapeVolume(const Shape& shape);

// Mass properties for a uniform density (kg/m^3). The inertia is the closed
// form for spheres, boxes and capsules, and the polyhedral mass integrals
// (Mirtich 1996) for convex hulls. Not defined for planes.
MassProperties ComputeMassProperties(const Shape& shape, double density);

}  // namespace contactsim
