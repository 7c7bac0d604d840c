// Volume integrals of a closed polyhedron with planar polygonal faces, by the
// divergence theorem in its signed-tetrahedron form: fan-triangulate every
// face and sum, for each triangle (a, b, c) seen from a reference point r,
// the integrals over the signed tetrahedron (r, a, b, c). They are exact
// polynomials (Mirtich 1996, "Fast and accurate computation of polyhedral
// mass properties", gives the same values by projection onto a face plane).
#pragma once

#include "service/physics/convex_hull.h"
#include "service/physics/math.h"

namespace contactsim {

struct PolyhedronIntegrals {
  double volume = 0.0;                    // m^3, integral of 1
  Vec3 centroid = Vec3::Zero();           // m, (integral of p) / volume
  // m^5, integral of (p - centroid)(p - centroid)^T: the second moment about
  // the centroid, from which the inertia is rho (tr(C) 1 - C).
  Mat3 second_moment = Mat3::Zero();
};

// Integrals of the solid hull in its own (body) frame.
PolyhedronIntegrals ComputePolyhedronIntegrals(const ConvexHull& hull);

}  // namespace contactsim
