#include "service/contact/lcp/lemke_rows.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "service/contact/lcp/delassus.h"
#include "service/contact/lcp/mixed_lcp.h"
#include "service/contact/lcp/row_complementarity.h"

namespace contactsim {
namespace {

// Largest complementarity residual (m/s, N s, or their product) of an
// accepted solution: solved stacks end at 1e-10 or below, a basis spoiled
// by round-off at 0.1-2.
constexpr double kMaxResidual = 1e-7;

// kUpper: lambda <= 0 (a joint's upper limit); kBox: |lambda| <= hi (a
// joint's friction), the friction form with a fixed bound
enum class Kind { kFree, kUnilateral, kUpper, kFriction, kBox };

Status Classify(const std::vector<ConstraintRow>& rows, std::vector<Kind>* kinds) {
  kinds->resize(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const ConstraintRow& r = rows[k];
    if (r.normal_row >= 0) {
      if (static_cast<size_t>(r.normal_row) >= rows.size() || rows[r.normal_row].normal_row >= 0 ||
          rows[r.normal_row].lo != 0.0) {
        return Status::InvalidArgument("row " + std::to_string(k) + ": normal_row " +
                                       std::to_string(r.normal_row) + " is not a unilateral row");
      }
      (*kinds)[k] = Kind::kFriction;
    } else if (r.lo == -ConstraintRow::kInf && r.hi == ConstraintRow::kInf) {
      (*kinds)[k] = Kind::kFree;
    } else if (r.lo == 0.0 && r.hi == ConstraintRow::kInf) {
      (*kinds)[k] = Kind::kUnilateral;
    } else if (r.lo == -ConstraintRow::kInf && r.hi == 0.0) {
      (*kinds)[k] = Kind::kUpper;
    } else if (std::isfinite(r.hi) && r.hi > 0.0 && r.lo == -r.hi) {
      (*kinds)[k] = Kind::kBox;
    } else {
      return Status::InvalidArgument("row " + std::to_string(k) + ": bounds [" + std::to_string(r.lo) + ", " +
                                     std::to_string(r.hi) + "] have no LCP form here (lemke takes free, [0, inf) "
                                     "friction and [-hi, hi] rows)");
    }
  }
  return Status::Ok();
}

}  // namespace

Status SolveRowsLemke(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                      const LemkeOptions& options, SolveReport* report) {
  *report = SolveReport();
  std::vector<Kind> kinds;
  if (Status st = Classify(rows, &kinds); !st.ok()) return st;
  const int m = static_cast<int>(rows.size());
  if (m == 0) {
    report->converged = true;
    return Status::Ok();
  }

  // variables: one per free or unilateral row; b+, b-, g per friction row
  std::vector<int> var(m), minus(m, -1), slip(m, -1);
  int nv = 0;
  for (int k = 0; k < m; ++k) {
    var[k] = nv++;
    if (kinds[k] == Kind::kFriction || kinds[k] == Kind::kBox) minus[k] = nv++, slip[k] = nv++;
  }
  // lambda = P y (an upper-limit row's variable is -lambda >= 0)
  MatX P = MatX::Zero(m, nv);
  for (int k = 0; k < m; ++k) {
    P(k, var[k]) = kinds[k] == Kind::kUpper ? -1.0 : 1.0;
    if (minus[k] >= 0) P(k, minus[k]) = -1.0;
  }
  MatX G = DenseDelassus(rows, bodies);
  for (int k = 0; k < m; ++k) G(k, k) += rows[k].cfm;  // a compliant row: J v + cfm lambda = rhs
  const MatX GP = G * P;
  VecX c = RowVelocities(rows, bodies);
  for (int k = 0; k < m; ++k) c[k] -= rows[k].rhs;

  MatX A = MatX::Zero(nv, nv);
  VecX b = VecX::Zero(nv);
  std::vector<bool> free(nv, false);
  for (int k = 0; k < m; ++k) {
    const double sign = kinds[k] == Kind::kUpper ? -1.0 : 1.0;  // w = -(G lambda + c) >= 0 for lambda <= 0
    A.row(var[k]) = sign * GP.row(k);
    b[var[k]] = sign * c[k];
    if (kinds[k] == Kind::kFree) free[var[k]] = true;
    if (kinds[k] != Kind::kFriction && kinds[k] != Kind::kBox) continue;
    A(var[k], slip[k]) += 1.0;
    A.row(minus[k]) = -GP.row(k);
    A(minus[k], slip[k]) += 1.0;
    b[minus[k]] = -c[k];
    // the slack of the bound: mu lambda_n - |lambda|, or hi - |lambda|
    if (kinds[k] == Kind::kFriction) A(slip[k], var[rows[k].normal_row]) = rows[k].mu;
    if (kinds[k] == Kind::kBox) b[slip[k]] = rows[k].hi;
    A(slip[k], var[k]) = -1.0;
    A(slip[k], minus[k]) = -1.0;
  }

  // Jacobi scaling, w' = S w = (S A S) z' + S b with z = S z' and S =
  // diag(A)^-1/2 (1 where A_ii = 0: the slip rows): the same LCP, as S is
  // positive diagonal, but with unit diagonal. A light body under a heavy
  // one spreads A's diagonal over 1/m_light .. 1/m_heavy, and unscaled the
  // pivots lost so much to round-off that Lemke "solved" a 1:100 stack with
  // complementarity violated by 2 m/s and the top box sank through.
  VecX scale = VecX::Ones(nv);
  for (int i = 0; i < nv; ++i) {
    if (A(i, i) > 0.0) scale[i] = 1.0 / std::sqrt(A(i, i));
  }
  const MatX A_scaled = scale.asDiagonal() * A * scale.asDiagonal();
  const VecX b_scaled = scale.cwiseProduct(b);
  LcpSolution sol = SolveMixedLcp(A_scaled, b_scaled, free, options);
  report->iterations = sol.pivots;
  report->outcome = sol.outcome;
  if (sol.outcome != LcpOutcome::kSolved) return Status::Ok();
  sol.z = scale.cwiseProduct(sol.z);
  sol.w = sol.w.cwiseQuotient(scale);
  for (int k = 0; k < nv; ++k) {
    const double wk = sol.w[k], zk = sol.z[k];
    report->residual = std::max(report->residual, free[k] ? std::abs(wk) : std::max({-wk, -zk, std::abs(wk * zk)}));
  }
  // a basis the pivots reached through round-off is no solution: the
  // caller falls back (lcp_method.h) instead of applying it
  if (!(report->residual <= kMaxResidual)) {
    report->outcome = LcpOutcome::kSingular;
    return Status::Ok();
  }
  report->converged = true;
  const VecX lambda = P * sol.z;
  for (int k = 0; k < m; ++k) {
    rows[k].lambda = lambda[k];
    rows[k].Apply(lambda[k], bodies);
  }
  report->complementarity = ComplementarityError(rows, bodies, FrictionSet::kPyramid);
  return Status::Ok();
}

}  // namespace contactsim
