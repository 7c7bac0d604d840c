#include "service/contact/soft/soft_ratio_solve.h"

#include <algorithm>
#include <limits>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Whether the dynamic bodies that touch something differ in mass by `ratio`:
// when not, no component can, and the step pays one pass over its points.
bool RatioReached(const std::vector<SoftBody>& bodies, const std::vector<SoftPoint>& points, double ratio) {
  double light = 0.0, heavy = kInf;  // inverse masses
  for (const SoftPoint& p : points) {
    for (int i : {p.a, p.b}) {
      if (bodies[i].inv_mass <= 0.0) continue;
      light = std::max(light, bodies[i].inv_mass);
      heavy = std::min(heavy, bodies[i].inv_mass);
    }
  }
  return light >= ratio * heavy;
}

}  // namespace

void SoftRatioSolve::Prepare(const SubspaceOptions& options, const std::vector<SoftBody>& bodies,
                             std::vector<SoftPoint>& points) {
  options_ = options;
  Select(bodies, points, options.mass_ratio);
  if (selected_.empty()) return;
  for (int k : selected_) {
    SoftPoint& p = points[k];
    const int body = bodies[p.a].inv_mass > 0.0 ? p.a : p.b;
    p.soft = LoadedSoftness(p.soft, std::min(1.0, p.mass_n / load_mass_[body]));
  }
  // the solve's bodies: those of the selected points, with the step's start
  // inertia (the points' Jacobians are the step's start too)
  slot_of_body_.assign(bodies.size(), -1);
  body_of_slot_.clear();
  solver_bodies_.clear();
  for (int k : selected_) {
    for (int i : {points[k].a, points[k].b}) {
      if (bodies[i].inv_mass <= 0.0 || slot_of_body_[i] >= 0) continue;
      slot_of_body_[i] = static_cast<int>(body_of_slot_.size());
      body_of_slot_.push_back(i);
      SolverBody s;
      s.inv_mass = bodies[i].inv_mass;
      s.inv_inertia = bodies[i].inv_inertia;
      solver_bodies_.push_back(s);
    }
  }
}

void SoftRatioSolve::Select(const std::vector<SoftBody>& bodies, const std::vector<SoftPoint>& points,
                            double ratio) {
  selected_.clear();
  if (ratio <= 0.0 || points.empty() || !RatioReached(bodies, points, ratio)) return;
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  for (const SoftPoint& p : points) {
    if (bodies[p.a].inv_mass > 0.0 && bodies[p.b].inv_mass > 0.0) sets.Join(p.a, p.b);
  }
  std::vector<double> light(n, 0.0), heavy(n, kInf);  // inverse masses per root
  for (const SoftPoint& p : points) {
    for (int i : {p.a, p.b}) {
      if (bodies[i].inv_mass <= 0.0) continue;
      const int root = sets.Root(i);
      light[root] = std::max(light[root], bodies[i].inv_mass);
      heavy[root] = std::min(heavy[root], bodies[i].inv_mass);
    }
  }
  load_mass_.assign(n, 0.0);
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    const SoftPoint& p = points[k];
    const int body = bodies[p.a].inv_mass > 0.0 ? p.a : p.b;
    if (bodies[body].inv_mass <= 0.0) continue;
    const int root = sets.Root(body);
    if (light[root] < ratio * heavy[root]) continue;
    selected_.push_back(k);
    load_mass_[p.a] = load_mass_[p.b] = 1.0 / heavy[root];
  }
}

void SoftRatioSolve::BuildRows(const SoftPass& pass, const std::vector<SoftPoint>& points,
                               const std::vector<SoftBody>& bodies) {
  rows_.resize(3 * selected_.size());
  for (size_t i = 0; i < selected_.size(); ++i) {
    const SoftPoint& p = points[selected_[i]];
    const int a = slot_of_body_[p.a], b = slot_of_body_[p.b];
    const SoftRowTarget target = SoftNormalTarget(pass, p, SoftSeparation(p, bodies[p.a], bodies[p.b]));
    const Vec3* dirs[3] = {&p.n, &p.t1, &p.t2};
    const Vec3* ja[3] = {&p.ra_n, &p.ra_t1, &p.ra_t2};
    const Vec3* jb[3] = {&p.rb_n, &p.rb_t1, &p.rb_t2};
    const double lambdas[3] = {p.lambda_n, p.lambda_t1, p.lambda_t2};
    for (int d = 0; d < 3; ++d) {
      ConstraintRow& r = rows_[3 * i + d];
      r = ConstraintRow{};
      r.a = a, r.b = b;
      r.lin_a = -*dirs[d], r.ang_a = -*ja[d];
      r.lin_b = *dirs[d], r.ang_b = *jb[d];
      r.lambda = lambdas[d];
      if (d == 0) {
        r.rhs = -target.bias;
        // the fixed point of the soft row's update, J v + bias + cfm lambda = 0 (softness.h)
        r.cfm = target.impulse_scale / (target.mass_scale * p.mass_n);
        r.lo = 0.0;
      } else {
        r.normal_row = static_cast<int>(3 * i);
        r.mu = p.friction;
      }
    }
  }
  for (size_t s = 0; s < body_of_slot_.size(); ++s) {
    solver_bodies_[s].v = bodies[body_of_slot_[s]].v;
    solver_bodies_[s].w = bodies[body_of_slot_[s]].w;
  }
}

void SoftRatioSolve::WriteBack(std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) const {
  for (size_t s = 0; s < body_of_slot_.size(); ++s) {
    bodies[body_of_slot_[s]].v = solver_bodies_[s].v;
    bodies[body_of_slot_[s]].w = solver_bodies_[s].w;
  }
  // Friction that slides here is held at +-mu lambda_n per tangent (the
  // subspace solve's bounds) until the next pass sweeps it onto the disk.
  // Projecting it onto the disk here instead kicked the light body between
  // two heavy ones by the difference: a 0.02 kg box between two 20 kg boxes
  // was squeezed out and the top box fell 100 mm.
  for (size_t i = 0; i < selected_.size(); ++i) {
    SoftPoint& p = points[selected_[i]];
    p.max_push = std::max(p.max_push, rows_[3 * i].lambda - p.lambda_n);
    p.lambda_n = rows_[3 * i].lambda;
    p.lambda_t1 = rows_[3 * i + 1].lambda;
    p.lambda_t2 = rows_[3 * i + 2].lambda;
  }
}

void SoftRatioSolve::Solve(const SoftPass& pass, std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) {
  if (selected_.empty()) return;
  BuildRows(pass, points, bodies);
  subspace_.Solve(rows_, solver_bodies_, options_);
  WriteBack(points, bodies);
}

}  // namespace contactsim
