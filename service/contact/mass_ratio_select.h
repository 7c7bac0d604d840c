// Which contact points need a direct solve because they join bodies of very
// different mass (subspace_solve.h): the points of each component of
// dynamic bodies joined by points whose heaviest body is at least `ratio`
// times its lightest. Shared by the soft and xpbd steps, whose points and
// bodies both carry `a`, `b` and `inv_mass`.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "service/contact/solver_body.h"
#include "service/contact/union_find.h"

namespace contactsim {

// The selected points (indices, ascending). `load_mass`, if given, gets per
// body the heaviest mass of its component (0 for bodies of no selected
// point). Worlds whose touching bodies are all within `ratio` pay one pass
// over the points; ratio <= 0 selects nothing.
template <class Body, class Point>
std::vector<int> SelectMassRatioPoints(const std::vector<Body>& bodies, const std::vector<Point>& points, double ratio,
                                       std::vector<double>* load_mass = nullptr) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<int> selected;
  if (ratio <= 0.0 || points.empty()) return selected;
  double light = 0.0, heavy = kInf;  // inverse masses
  for (const Point& p : points) {
    for (int i : {p.a, p.b}) {
      if (bodies[i].inv_mass <= 0.0) continue;
      light = std::max(light, bodies[i].inv_mass);
      heavy = std::min(heavy, bodies[i].inv_mass);
    }
  }
  if (light < ratio * heavy) return selected;
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  for (const Point& p : points) {
    if (bodies[p.a].inv_mass > 0.0 && bodies[p.b].inv_mass > 0.0) sets.Join(p.a, p.b);
  }
  std::vector<double> lightest(n, 0.0), heaviest(n, kInf);  // inverse masses per root
  for (const Point& p : points) {
    for (int i : {p.a, p.b}) {
      if (bodies[i].inv_mass <= 0.0) continue;
      const int root = sets.Root(i);
      lightest[root] = std::max(lightest[root], bodies[i].inv_mass);
      heaviest[root] = std::min(heaviest[root], bodies[i].inv_mass);
    }
  }
  if (load_mass != nullptr) load_mass->assign(n, 0.0);
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    const Point& p = points[k];
    const int body = bodies[p.a].inv_mass > 0.0 ? p.a : p.b;
    if (bodies[body].inv_mass <= 0.0) continue;
    const int root = sets.Root(body);
    if (lightest[root] < ratio * heaviest[root]) continue;
    selected.push_back(k);
    if (load_mass != nullptr) (*load_mass)[p.a] = (*load_mass)[p.b] = 1.0 / heaviest[root];
  }
  return selected;
}

// The direct solve's bodies: those of the selected points, each a
// SolverBody with the inverse mass and inertia of `bodies` (the step's
// start, as the points' Jacobians are).
struct RatioSolveBodies {
  std::vector<int> slot_of_body;  // world body index -> solver body, or -1
  std::vector<int> body_of_slot;  // solver body -> world body index
  std::vector<SolverBody> solver;

  template <class Body, class Point>
  void Build(const std::vector<Body>& bodies, const std::vector<Point>& points, const std::vector<int>& selected) {
    slot_of_body.assign(bodies.size(), -1);
    body_of_slot.clear();
    solver.clear();
    for (int k : selected) {
      for (int i : {points[k].a, points[k].b}) {
        if (bodies[i].inv_mass <= 0.0 || slot_of_body[i] >= 0) continue;
        slot_of_body[i] = static_cast<int>(body_of_slot.size());
        body_of_slot.push_back(i);
        SolverBody s;
        s.inv_mass = bodies[i].inv_mass;
        s.inv_inertia = bodies[i].inv_inertia;
        solver.push_back(s);
      }
    }
  }
};

}  // namespace contactsim
