#include "service/physics/hull_vertex_budget.h"

#include <algorithm>
#include <array>
#include <string>

#include "service/physics/quickhull.h"

namespace contactsim {

Status CheckMaxHullVertices(int max_vertices) {
  if (max_vertices == 0 || max_vertices >= kMinHullVertices) return Status::Ok();
  return Status::InvalidArgument("max_hull_vertices must be 0 (every vertex) or at least " +
                                 std::to_string(kMinHullVertices) + ", got " + std::to_string(max_vertices));
}

Status ResolveMaxHullVertices(int requested, int* max_vertices) {
  if (requested == -1 || requested == 0 || requested >= kMinHullVertices) {
    *max_vertices = requested == -1 ? 0 : requested == 0 ? kDefaultMaxHullVertices : requested;
    return Status::Ok();
  }
  return Status::InvalidArgument("max_hull_vertices must be -1 (every vertex), 0 (the default, " +
                                 std::to_string(kDefaultMaxHullVertices) + ") or at least " +
                                 std::to_string(kMinHullVertices) + ", got " + std::to_string(requested));
}

namespace {

// The indices of the points the triangles use, once each, ascending.
std::vector<int> CornerIndices(std::size_t points, const std::vector<std::array<int, 3>>& triangles) {
  std::vector<bool> used(points, false);
  for (const auto& t : triangles) used[t[0]] = used[t[1]] = used[t[2]] = true;
  std::vector<int> out;
  for (std::size_t i = 0; i < points; ++i) {
    if (used[i]) out.push_back(static_cast<int>(i));
  }
  return out;
}

// A triangle's plane: a corner, its (unnormalised) normal and that
// normal's length.
struct Plane {
  Vec3 a, n;
  double len;
};

// The planes of the triangles of `hull_points` with a non-zero area.
std::vector<Plane> TrianglePlanes(const std::vector<Vec3>& hull_points,
                                  const std::vector<std::array<int, 3>>& triangles) {
  std::vector<Plane> planes;
  for (const auto& t : triangles) {
    const Vec3& a = hull_points[t[0]];
    const Vec3 n = (hull_points[t[1]] - a).cross(hull_points[t[2]] - a);
    const double len = n.norm();
    if (len > 0.0) planes.push_back({a, n, len});
  }
  return planes;
}

// How far `p` lies above a hull with these face planes: its largest height
// over them (<= 0 inside).
double HeightAbove(const Vec3& p, const std::vector<Plane>& planes) {
  double height = -1e300;
  for (const Plane& f : planes) height = std::max(height, f.n.dot(p - f.a) / f.len);
  return height;
}

// Greedy choice among the full hull's `vertices`: from the initial
// tetrahedron, add the vertex highest above the hull of those kept so far,
// until `max_vertices` are kept or none lies above it by more than `tol`.
Status GreedyVertices(const std::vector<Vec3>& vertices, int max_vertices, double tol, std::vector<int>* chosen) {
  std::array<int, 4> corners;
  if (Status st = InitialTetrahedron(vertices, tol, &corners); !st.ok()) return st;
  chosen->assign(corners.begin(), corners.end());
  std::vector<bool> taken(vertices.size(), false);
  for (int i : corners) taken[i] = true;
  std::vector<Vec3> kept;
  std::vector<std::array<int, 3>> triangles;
  while (static_cast<int>(chosen->size()) < max_vertices) {
    kept.clear();
    for (int i : *chosen) kept.push_back(vertices[i]);
    if (Status st = Quickhull(kept, tol, &triangles); !st.ok()) return st;
    const std::vector<Plane> planes = TrianglePlanes(kept, triangles);
    int eye = -1;
    double highest = tol;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      if (taken[i]) continue;
      const double h = HeightAbove(vertices[i], planes);
      if (h > highest) highest = h, eye = static_cast<int>(i);
    }
    if (eye < 0) break;
    taken[eye] = true;
    chosen->push_back(eye);
  }
  std::sort(chosen->begin(), chosen->end());
  return Status::Ok();
}

}  // namespace

Status BudgetedHullPoints(const std::vector<Vec3>& points, int max_vertices, std::vector<Vec3>* kept) {
  if (Status st = CheckMaxHullVertices(max_vertices); !st.ok()) return st;
  if (points.size() < 4) {
    return Status::InvalidArgument("convex hull needs at least 4 points, got " + std::to_string(points.size()));
  }
  for (const Vec3& p : points) {
    if (!IsFinite(p)) return Status::InvalidArgument("a hull point is not finite");
  }
  const double tol = HullTolerance(points);
  std::vector<std::array<int, 3>> triangles;
  if (Status st = Quickhull(points, tol, &triangles); !st.ok()) return st;
  // the full hull's vertices, in the input's order; the greedy choice
  // among them when there are more than the budget
  std::vector<Vec3> vertices;
  for (int i : CornerIndices(points.size(), triangles)) vertices.push_back(points[i]);
  kept->clear();
  if (max_vertices == 0 || static_cast<int>(vertices.size()) <= max_vertices) {
    *kept = vertices;
    return Status::Ok();
  }
  std::vector<int> chosen;
  if (Status st = GreedyVertices(vertices, max_vertices, tol, &chosen); !st.ok()) return st;
  for (int i : chosen) kept->push_back(vertices[i]);
  return Status::Ok();
}

}  // namespace contactsim
