#include "service/contact/soft/soft_ratio_solve.h"

#include <algorithm>

#include "service/contact/mass_ratio_select.h"

namespace contactsim {

void SoftRatioSolve::Select(const SubspaceOptions& options, const std::vector<SoftBody>& bodies,
                            const std::vector<SoftPoint>& points) {
  options_ = options;
  selected_ = SelectMassRatioPoints(bodies, points, options.mass_ratio, &load_mass_);
}

void SoftRatioSolve::Stiffen(const std::vector<SoftBody>& bodies, std::vector<SoftPoint>& points) {
  if (selected_.empty()) return;
  for (int k : selected_) {
    SoftPoint& p = points[k];
    const int body = bodies[p.a].inv_mass > 0.0 ? p.a : p.b;
    p.soft = LoadedSoftness(p.soft, std::min(1.0, p.mass_n / load_mass_[body]));
  }
  slots_.Build(bodies, points, selected_);
}

void SoftPointRows(const SoftPass& pass, const SoftPoint& p, const std::vector<SoftBody>& bodies, int a, int b,
                   int normal_row, ConstraintRow rows[3]) {
  const SoftRowTarget target = SoftNormalTarget(pass, p, SoftSeparation(p, bodies[p.a], bodies[p.b]));
  const Vec3* dirs[3] = {&p.n, &p.t1, &p.t2};
  const Vec3* ja[3] = {&p.ra_n, &p.ra_t1, &p.ra_t2};
  const Vec3* jb[3] = {&p.rb_n, &p.rb_t1, &p.rb_t2};
  const double lambdas[3] = {p.lambda_n, p.lambda_t1, p.lambda_t2};
  for (int d = 0; d < 3; ++d) {
    ConstraintRow& r = rows[d];
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
      r.normal_row = normal_row;
      r.mu = p.friction;
    }
  }
}

void ReadSoftPointRows(const ConstraintRow rows[3], SoftPoint& p) {
  p.max_push = std::max(p.max_push, rows[0].lambda - p.lambda_n);
  p.lambda_n = rows[0].lambda;
  p.lambda_t1 = rows[1].lambda;
  p.lambda_t2 = rows[2].lambda;
}

void SoftRatioSolve::BuildRows(const SoftPass& pass, const std::vector<SoftPoint>& points,
                               const std::vector<SoftBody>& bodies) {
  rows_.resize(3 * selected_.size());
  for (size_t i = 0; i < selected_.size(); ++i) {
    const SoftPoint& p = points[selected_[i]];
    SoftPointRows(pass, p, bodies, slots_.slot_of_body[p.a], slots_.slot_of_body[p.b], static_cast<int>(3 * i),
                  &rows_[3 * i]);
  }
  for (size_t s = 0; s < slots_.body_of_slot.size(); ++s) {
    slots_.solver[s].v = bodies[slots_.body_of_slot[s]].v;
    slots_.solver[s].w = bodies[slots_.body_of_slot[s]].w;
  }
}

void SoftRatioSolve::WriteBack(std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) const {
  for (size_t s = 0; s < slots_.body_of_slot.size(); ++s) {
    bodies[slots_.body_of_slot[s]].v = slots_.solver[s].v;
    bodies[slots_.body_of_slot[s]].w = slots_.solver[s].w;
  }
  for (size_t i = 0; i < selected_.size(); ++i) ReadSoftPointRows(&rows_[3 * i], points[selected_[i]]);
}

void SoftRatioSolve::Solve(const SoftPass& pass, std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) {
  if (selected_.empty()) return;
  BuildRows(pass, points, bodies);
  subspace_.Solve(rows_, slots_.solver, options_);
  WriteBack(points, bodies);
}

}  // namespace contactsim
