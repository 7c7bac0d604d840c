#include "service/physics/hull_memo.h"

#include <cstring>

#include "service/physics/fnv1a.h"
#include "service/physics/hull_vertex_budget.h"

namespace contactsim {
namespace {

uint64_t PointsKey(const std::vector<Vec3>& points) {
  Fnv1a h;
  h.Bytes(points.data(), points.size() * sizeof(Vec3));
  return h.h ^ points.size();
}

// the same bit patterns (== would take -0.0 for 0.0, which a hull may keep)
bool SamePoints(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

}  // namespace

Status HullMemo::BudgetedPoints(const std::vector<Vec3>& points, int max_vertices, std::vector<Vec3>* kept) {
  const uint64_t key = PointsKey(points);
  for (auto [it, end] = budgeted_.equal_range(key); it != end; ++it) {
    if (it->second.max_vertices == max_vertices && SamePoints(it->second.points, points)) {
      *kept = it->second.kept;
      return Status::Ok();
    }
  }
  Status st = BudgetedHullPoints(points, max_vertices, kept);
  if (st.ok()) budgeted_.emplace(key, Budgeted{points, max_vertices, *kept});
  return st;
}

Status HullMemo::Hull(const std::vector<Vec3>& points, std::shared_ptr<const ConvexHull>* hull, Vec3* centroid) {
  const uint64_t key = PointsKey(points);
  for (auto [it, end] = built_.equal_range(key); it != end; ++it) {
    if (SamePoints(it->second.points, points)) {
      *hull = it->second.hull;
      *centroid = it->second.centroid;
      return Status::Ok();
    }
  }
  Status st = BuildConvexHull(points, hull, centroid);
  if (st.ok()) built_.emplace(key, Built{points, *hull, *centroid});
  return st;
}

}  // namespace contactsim
