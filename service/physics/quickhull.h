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

// Triangles of the hull of `points`, as indices into `points`, wound
// counter-clockwise seen from outside. A point closer than `tolerance` (m)
// to a face plane counts as on it, so nearly coplanar points do not create
// slivers. Fails when the points span no volume (collinear or coplanar
// within the tolerance). Expects finite points, at least four.
Status Quickhull(const std::vector<Vec3>& points, double tolerance,
                 std::vector<std::array<int, 3>>* triangles);

}  // namespace contactsim
