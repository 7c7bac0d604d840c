// The triangulated hull of a point cloud by Quickhull (Barber, Dobkin and
// Huhdanpaa 1996, "The quickhull algorithm for convex hulls", ACM TOMS
// 22(4)), as the qhull library implements it. BuildConvexHull
// (convex_hull.h) turns the triangles into polygon faces; this is its
// first stage.
#pragma once

#include <array>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

// The distance (m) within which a point counts as on a face plane of the
// hull of `points` (finite): 1e-9 of the cloud's size plus its distance
// from the origin, whose round-off the plane offsets carry. 1e-9 is far
// above the round-off of a plane through three points (~1e-15 relative)
// and far below any geometric feature a contact simulation resolves.
double HullTolerance(const std::vector<Vec3>& points);

// Triangles of the hull of `points` (by qhull), as indices into `points`,
// wound counter-clockwise seen from outside, the largest first. A point
// closer than `tolerance` (m) to a face plane counts as on it, so nearly
// coplanar points do not create slivers. Fails, saying why, when the points
// span no volume (they coincide, or are collinear or coplanar within the
// tolerance). Expects finite points, at least four.
Status Quickhull(const std::vector<Vec3>& points, double tolerance, std::vector<std::array<int, 3>>* triangles);

// Four points of `points` spanning the largest volume a quick search finds:
// the two furthest apart of the six axis extremes, the point furthest from
// their line, and the point furthest from the plane of those three. Fails
// as Quickhull does when they span no volume within `tolerance`.
Status InitialTetrahedron(const std::vector<Vec3>& points, double tolerance, std::array<int, 4>* corners);

}  // namespace contactsim
