#include "service/physics/hull_vertex_budget.h"

#include <algorithm>
#include <array>
#include <string>

#include "service/physics/incremental_hull.h"
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

// Greedy choice among the full hull's `vertices`: from the initial
// tetrahedron, add the vertex highest above the hull of those kept so far,
// until `max_vertices` are kept or none lies above it by more than `tol`.
// One hull grows by a cone each round (incremental_hull.h), a fraction
// of the cost of a hull from scratch each round (BENCHMARKS.md, "Robot
// models: load time").
Status GreedyVertices(const std::vector<Vec3>& vertices, int max_vertices, double tol, std::vector<int>* chosen) {
  std::array<int, 4> corners;
  if (Status st = InitialTetrahedron(vertices, tol, &corners); !st.ok()) return st;
  chosen->assign(corners.begin(), corners.end());
  IncrementalHull hull(vertices, tol);
  hull.Start(corners);
  while (static_cast<int>(chosen->size()) < max_vertices) {
    const int eye = hull.Highest();
    if (eye < 0) break;
    if (Status st = hull.Add(eye); !st.ok()) return st;
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
