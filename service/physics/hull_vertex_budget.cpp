#include "service/physics/hull_vertex_budget.h"

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

Status BudgetedHullPoints(const std::vector<Vec3>& points, int max_vertices, std::vector<Vec3>* kept) {
  if (Status st = CheckMaxHullVertices(max_vertices); !st.ok()) return st;
  if (points.size() < 4) {
    return Status::InvalidArgument("convex hull needs at least 4 points, got " + std::to_string(points.size()));
  }
  for (const Vec3& p : points) {
    if (!IsFinite(p)) return Status::InvalidArgument("a hull point is not finite");
  }
  std::vector<std::array<int, 3>> triangles;
  Status st = Quickhull(points, HullTolerance(points), &triangles, max_vertices);
  if (!st.ok()) return st;
  // the triangles' corners, once each, in the input's order
  std::vector<bool> used(points.size(), false);
  for (const auto& t : triangles) used[t[0]] = used[t[1]] = used[t[2]] = true;
  kept->clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (used[i]) kept->push_back(points[i]);
  }
  return Status::Ok();
}

}  // namespace contactsim
