// An upper bound on the depth of the contacts the narrowphase reports for a
// pair, from one direction: what a look-ahead over a step (impulse's impact
// search) can ask instead of a full separating-axis test when all it needs
// to know is that no contact of the pair is deeper than some depth.
//
// For convex A and B and any unit u (from A to B), the overlap of their
// projections on u,
//   o(u) = max_{p in A} u.p - min_{p in B} u.p,
// is at least the translational penetration depth, which is the least
// o(u) over all directions (the distance of the origin from the boundary
// of A - B; Cameron and Culley 1986), and a separated pair has an axis of
// negative overlap among the separating-axis candidates. The narrowphase's
// polyhedron contacts are no deeper than the overlap along the axis it
// chose (a face's clipped points and its deepest vertex lie within the
// projections; an edge pair's point has the axis's depth;
// polyhedron_manifold.h), and that axis is at most kSatMaxBias +
// kSatAbsTolerance deeper than the least candidate (polyhedron_sat.h).
// Against a plane each vertex's depth is the overlap along the plane's
// normal itself. So every contact of two polyhedra, or of a polyhedron and
// a plane, is at most
//   max(o(u), 0) + kSatMaxBias + kSatAbsTolerance
// deep, for every u; a compound's overlap along u is that of the union of
// its children, at least any child pair's.
#pragma once

#include "service/physics/rigid_body.h"

namespace contactsim {

// The bound above (m) for bodies a and b along unit u_AB (world, from a to
// b): a box, a convex hull, a plane or a compound of those on each side, a
// plane only along its own normal (within 1e-12 of it). +infinity for any
// other shape or direction (no bound known), so callers fall back to the
// narrowphase.
double ContactDepthBound(const RigidBody& a, const RigidBody& b, const Vec3& u_AB);

}  // namespace contactsim
