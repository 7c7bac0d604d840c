#include "service/contact/lcp/pgs.h"

#include <algorithm>
#include <cmath>

#include "service/contact/lcp/friction_disk.h"
#include "service/contact/lcp/row_complementarity.h"

namespace contactsim {

void PgsSolver::Prepare(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                        int world_slot, int sink_slot) {
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
    r.second = IsFrictionPairLead(rows, order_[k]) ? position_[order_[k] + 1] : -1;
    r.in_pair = IsFrictionPairSecond(rows, order_[k]);
    r.source = order_[k];
    r.lambda = c.lambda;
  }
}

double PgsSolver::SolvePair(Row& r1, Row& r2) {
  // both rows act on the same two bodies (one contact)
  const Velocity A = vel_[r1.a];
  const Velocity B = vel_[r1.b];
  const double jv1 = r1.ja_lin.dot(A.v) + r1.ja_ang.dot(A.w) + r1.jb_lin.dot(B.v) + r1.jb_ang.dot(B.w);
  const double jv2 = r2.ja_lin.dot(A.v) + r2.ja_ang.dot(A.w) + r2.jb_lin.dot(B.v) + r2.jb_ang.dot(B.w);
  const double trace = r1.diag + r2.diag;
  const double eta = trace > 0.0 ? 2.0 / trace : 0.0;
  double l1 = r1.lambda + eta * (r1.rhs - jv1);
  double l2 = r2.lambda + eta * (r2.rhs - jv2);
  ProjectOntoDisk(std::max(0.0, r1.mu * rows_[r1.normal_row].lambda), &l1, &l2);
  const double d1 = l1 - r1.lambda, d2 = l2 - r2.lambda;
  r1.lambda = l1;
  r2.lambda = l2;
  vel_[r1.write_a] = {A.v + r1.ma_lin * d1 + r2.ma_lin * d2, A.w + r1.ma_ang * d1 + r2.ma_ang * d2};
  vel_[r1.write_b] = {B.v + r1.mb_lin * d1 + r2.mb_lin * d2, B.w + r1.mb_ang * d1 + r2.mb_ang * d2};
  return std::max(std::abs(d1) * r1.diag, std::abs(d2) * r2.diag);
}

SolveReport PgsSolver::Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                             const PgsOptions& options) {
  SolveReport report;
  const int world_slot = static_cast<int>(bodies.size());
  const int sink_slot = world_slot + 1;
  vel_.resize(bodies.size() + 2);
  for (size_t i = 0; i < bodies.size(); ++i) vel_[i] = {bodies[i].v, bodies[i].w};
  vel_[world_slot] = {Vec3::Zero(), Vec3::Zero()};
  vel_[sink_slot] = {Vec3::Zero(), Vec3::Zero()};
  Prepare(rows, bodies, world_slot, sink_slot);

  // warm start
  for (const Row& r : rows_) {
    if (r.lambda != 0.0) Apply(r, vel_[r.a], vel_[r.b], r.lambda);
  }

  for (int it = 0; it < options.iterations; ++it) {
    double worst = 0.0;
    for (Row& r : rows_) {
      if (r.in_pair) continue;  // updated with its pair's first row
      if (r.second >= 0) {
        worst = std::max(worst, SolvePair(r, rows_[r.second]));
        continue;
      }
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
