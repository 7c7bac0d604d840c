// A convex hull simplified to a vertex budget, as robot meshes are loaded
// (MuJoCo's `maxhullvert`, Bullet's btShapeHull): the hull of a few hundred
// mesh vertices costs the separating-axis test hundreds of thousands of edge
// pairs, where a hull of a few dozen of its points keeps the shape within a
// millimetre or two at a fraction of the cost (docs/models.md, "Hull vertex
// budget").
//
// The points kept are chosen among the full hull's vertices (quickhull.h):
// after the extreme tetrahedron, each round adds the vertex furthest outside
// the hull of those kept so far, the greedy choice that shrinks the largest
// gap first (qhull's own `TA` stop takes the furthest point of the facet it
// happens to visit next, which left a 64-vertex ellipsoid 12% of its
// largest semi-axis away from the full hull against this choice's 2-6%). The
// simplified hull is the hull of the kept points: inside the full hull, and
// spanned by points of the mesh, so it never reaches beyond the surface the
// file describes.
#pragma once

#include <vector>

#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

// Robot meshes' default budget: 64 vertices, well under the ~300 to 600 of
// an arm link's full hull (the iiwa's), which keeps each link's surface
// within a few millimetres (docs/models.md gives the measured error).
// MuJoCo leaves maxhullvert unlimited unless asked; Bullet's btShapeHull
// keeps the supports along 42 directions.
constexpr int kDefaultMaxHullVertices = 64;
// The least budget: a tetrahedron.
constexpr int kMinHullVertices = 4;

// Ok for 0 (every vertex) or a budget of at least kMinHullVertices; an
// error naming the field and the value otherwise.
Status CheckMaxHullVertices(int max_vertices);

// A budget as the protocol and the scene files give it (0: the default,
// kDefaultMaxHullVertices; -1: every vertex; at least kMinHullVertices:
// itself) as BudgetedHullPoints takes it (0: every vertex); an error naming
// the field and the value for anything else.
Status ResolveMaxHullVertices(int requested, int* max_vertices);

// The points (a subset of `points`, in their order) whose hull is the
// budgeted hull of `points`; all the hull's vertices when it has no more
// than `max_vertices`. `max_vertices` 0 keeps every vertex of the full hull;
// otherwise it must pass CheckMaxHullVertices. Fails as BuildConvexHull
// does on fewer than four points or a flat cloud.
Status BudgetedHullPoints(const std::vector<Vec3>& points, int max_vertices, std::vector<Vec3>* kept);

}  // namespace contactsim
