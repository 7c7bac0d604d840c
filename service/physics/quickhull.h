// Quickhull in 3D (Barber, Dobkin and Huhdanpaa 1996, "The quickhull
// algorithm for convex hulls", ACM TOMS 22(4)): the triangulated hull of a
// point cloud. BuildConvexHull (convex_hull.h) turns the triangles into
// polygon faces; this is its first stage.
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

// Triangles of the hull of `points`, as indices into `points`, wound
// counter-clockwise seen from outside. A point closer than `tolerance` (m)
// to a face plane counts as on it, so nearly coplanar points do not create
// slivers. Fails when the points span no volume (collinear or coplanar
// within the tolerance). Expects finite points, at least four.
// `max_vertices` > 0 (at least 4) stops the build when that many points are
// on it, adding the point furthest outside the hull so far each time: the
// result is the hull of at most that many of the points, inside the full
// hull (see quickhull.cpp). 0 builds the full hull.
Status Quickhull(const std::vector<Vec3>& points, double tolerance,
                 std::vector<std::array<int, 3>>* triangles, int max_vertices = 0);

}  // namespace contactsim
