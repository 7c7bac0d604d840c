#include "service/contact/lcp/pgs.h"

#include <algorithm>
#include <cmath>

#include "service/contact/lcp/row_complementarity.h"

namespace contactsim {

SolveReport PgsSolver::Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                             const PgsOptions& options) {
  SolveReport report;
  const int world_slot = static_cast<int>(bodies.size());
  const int sink_slot = world_slot + 1;
  vel_.resize(bodies.size() + 2);
  for (size_t i = 0; i < bodies.size(); ++i) vel_[i] = {bodies[i].v, bodies[i].w};
  vel_[world_slot] = {Vec3::Zero(), Vec3::Zero()};
  vel_[sink_slot] = {Vec3::Zero(), Vec3::Zero()};

  schedule_.Order(rows, bodies, &order_);
  position_.resize(rows.size());
  for (size_t k = 0; k < order_.size(); ++k) position_[order_[k]] = static_cast<int>(k);

  // flat copy with M^-1 J^T; bodies without mass get zero blocks (their
  // velocity, e.g. a kinematic body's, still enters J v)
  rows_.resize(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const ConstraintRow& c = rows[order_[k]];
    Row& r = rows_[k];
    r.a = c.a >= 0 ? c.a : world_slot;
    r.b = c.b >= 0 ? c.b : world_slot;
    r.write_a = c.a >= 0 && bodies[c.a].inv_mass > 0.0 ? c.a : sink_slot;
    r.write_b = c.b >= 0 && bodies[c.b].inv_mass > 0.0 ? c.b : sink_slot;
    r.ja_lin = c.a >= 0 ? c.lin_a : Vec3::Zero();
    r.ja_ang = c.a >= 0 ? c.ang_a : Vec3::Zero();
    r.jb_lin = c.b >= 0 ? c.lin_b : Vec3::Zero();
    r.jb_ang = c.b >= 0 ? c.ang_b : Vec3::Zero();
    const SolverBody* A = c.a >= 0 ? &bodies[c.a] : nullptr;
    const SolverBody* B = c.b >= 0 ? &bodies[c.b] : nullptr;
    r.ma_lin = A ? Vec3(A->inv_mass * r.ja_lin) : Vec3::Zero();
    r.ma_ang = A ? Vec3(A->inv_inertia * r.ja_ang) : Vec3::Zero();
    r.mb_lin = B ? Vec3(B->inv_mass * r.jb_lin) : Vec3::Zero();
    r.mb_ang = B ? Vec3(B->inv_inertia * r.jb_ang) : Vec3::Zero();
    r.diag = c.Diagonal(bodies);
    r.inv_diag = r.diag > 0.0 ? 1.0 / r.diag : 0.0;
    r.rhs = c.rhs;
    r.lo = c.lo;
    r.hi = c.hi;
    r.mu = c.mu;
    r.normal_row = c.normal_row >= 0 ? position_[c.normal_row] : -1;
    r.source = order_[k];
    r.lambda = c.lambda;
  }

  // warm start
  for (const Row& r : rows_) {
    if (r.lambda != 0.0) Apply(r, vel_[r.a], vel_[r.b], r.lambda);
  }

  for (int it = 0; it < options.iterations; ++it) {
    double worst = 0.0;
    for (Row& r : rows_) {
      double lo = r.lo, hi = r.hi;
      if (r.normal_row >= 0) {
        hi = r.mu * rows_[r.normal_row].lambda;
        lo = -hi;
      }
      const Velocity A = vel_[r.a];
      const Velocity B = vel_[r.b];
      const double jv = r.ja_lin.dot(A.v) + r.ja_ang.dot(A.w) + r.jb_lin.dot(B.v) + r.jb_ang.dot(B.w);
      const double next = std::clamp(r.lambda + (r.rhs - jv) * r.inv_diag, lo, hi);
      const double d = next - r.lambda;
      r.lambda = next;
      Apply(r, A, B, d);
      worst = std::max(worst, std::abs(d) * r.diag);
    }
    report.iterations = it + 1;
    report.residual = worst;
    if (worst < options.tolerance) {
      report.converged = true;
      break;
    }
  }

  // the impulses go to the bodies through ConstraintRow::Apply, so dP and dL sum
  for (const Row& r : rows_) rows[r.source].lambda = r.lambda;
  for (ConstraintRow& row : rows) row.Apply(row.lambda, bodies);
  report.complementarity = ComplementarityError(rows, bodies);
  return report;
}

}  // namespace contactsim
