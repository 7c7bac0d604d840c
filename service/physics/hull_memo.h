// The hulls of one batch of bodies (a model's links), each computed once per
// distinct point set: a robot's left and right fingers read the same mesh,
// and its wheels are cylinders of one size, so their budgeted points and
// hulls are the same. Both functions are pure, so a remembered result is
// the one a new computation would give, bit for bit. Lives as long as the
// batch (one model build), so it holds no memory between loads.
#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

#include "service/physics/convex_hull.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

class HullMemo {
 public:
  // BudgetedHullPoints (hull_vertex_budget.h), remembered.
  Status BudgetedPoints(const std::vector<Vec3>& points, int max_vertices, std::vector<Vec3>* kept);

  // BuildConvexHull (convex_hull.h) with its centroid, remembered.
  Status Hull(const std::vector<Vec3>& points, std::shared_ptr<const ConvexHull>* hull, Vec3* centroid);

 private:
  struct Budgeted {
    std::vector<Vec3> points;
    int max_vertices;
    std::vector<Vec3> kept;
  };
  struct Built {
    std::vector<Vec3> points;
    std::shared_ptr<const ConvexHull> hull;
    Vec3 centroid;
  };
  // keyed by a hash of the points' bit patterns; equal points compared whole
  std::unordered_multimap<uint64_t, Budgeted> budgeted_;
  std::unordered_multimap<uint64_t, Built> built_;
};

}  // namespace contactsim
