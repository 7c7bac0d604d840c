// Signed distance from a point to a box or a convex polyhedron, with the
// nearest surface point and the outward normal there. Spheres are points with
// a radius and capsules segments with a radius, so their contacts with boxes
// and hulls follow from this function:
//   outside: the Euclidean distance to the nearest surface point;
//   inside:  minus the distance to the nearest face plane, max_f (n_f.p - o_f)
//            (exact for a convex polytope).
// The signed distance of a convex set is a convex, continuous function of p,
// which the capsule code relies on.
#pragma once

#include "service/collision/posed_polyhedron.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct SurfaceQuery {
  double distance = 0.0;        // m, > 0 outside, < 0 inside
  Vec3 point = Vec3::Zero();    // nearest surface point, world
  Vec3 normal = Vec3::UnitZ();  // unit outward normal there, world
  int feature = 0;              // face (or region) that holds the nearest point
};

// Box body, closed form in the box frame.
SurfaceQuery BoxSignedDistance(const RigidBody& box, const Vec3& p_W);

// Any posed polyhedron, by its faces: the nearest point lies on a face whose
// plane has p on its outer side (Ericson, "Real-Time Collision Detection", 5.1).
SurfaceQuery PolyhedronSignedDistance(const PosedPolyhedron& poly, const Vec3& p_W);

}  // namespace contactsim
