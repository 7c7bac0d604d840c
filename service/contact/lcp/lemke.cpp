#include "service/contact/lcp/lemke.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

namespace contactsim {
namespace {

// Tableau columns: w_0..w_{n-1}, z_0..z_{n-1}, the artificial z0, then the
// right-hand side. The w columns hold B^-1, since the first basis is w.
class Tableau {
 public:
  Tableau(const MatX& M, const VecX& q) : n_(static_cast<int>(q.size())), t_(n_, 2 * n_ + 2), basis_(n_) {
    t_.setZero();
    t_.leftCols(n_).setIdentity();
    t_.middleCols(n_, n_) = -M;
    t_.col(Artificial()).setConstant(-1.0);
    t_.col(Rhs()) = q;
    for (int i = 0; i < n_; ++i) basis_[i] = i;
  }

  int Artificial() const { return 2 * n_; }
  int Rhs() const { return 2 * n_ + 1; }
  int Complement(int var) const { return var < n_ ? var + n_ : var - n_; }
  int Basic(int row) const { return basis_[row]; }
  double At(int row, int col) const { return t_(row, col); }

  // -1 when row i's lexicographic key (rhs, B^-1 row) / t(i, col) is smaller
  // than row j's, +1 when larger, 0 when equal within tol.
  int CompareRatios(int i, int j, int col, double tol) const {
    const double ai = t_(i, col), aj = t_(j, col);
    const double ri = t_(i, Rhs()) / ai, rj = t_(j, Rhs()) / aj;
    if (std::abs(ri - rj) > tol * (1.0 + std::max(std::abs(ri), std::abs(rj)))) return ri < rj ? -1 : 1;
    for (int k = 0; k < n_; ++k) {
      const double ki = t_(i, k) / ai, kj = t_(j, k) / aj;
      if (std::abs(ki - kj) > tol * (1.0 + std::max(std::abs(ki), std::abs(kj)))) return ki < kj ? -1 : 1;
    }
    return 0;
  }
  bool RatioTied(int i, int j, int col, double tol) const {
    const double ri = t_(i, Rhs()) / t_(i, col), rj = t_(j, Rhs()) / t_(j, col);
    return std::abs(ri - rj) <= tol * (1.0 + std::max(std::abs(ri), std::abs(rj)));
  }

  // Gauss-Jordan pivot on (row, col); col becomes basic in row. Only the
  // pivot row's nonzero columns change the other rows: contact tableaus are
  // sparse (a row couples the few contacts of two bodies), so the update
  // touches a fraction of the 2n + 2 columns; skipping exact zeros leaves
  // every value as the full row operation would.
  void Pivot(int row, int col) {
    t_.row(row) /= t_(row, col);
    nonzero_.clear();
    for (int k = 0; k < t_.cols(); ++k) {
      if (t_(row, k) != 0.0) nonzero_.push_back(k);
    }
    const double* pivot = &t_(row, 0);
    for (int i = 0; i < n_; ++i) {
      if (i == row) continue;
      const double f = t_(i, col);
      if (f == 0.0) continue;
      double* target = &t_(i, 0);
      for (const int k : nonzero_) target[k] -= f * pivot[k];
    }
    basis_[row] = col;
  }

 private:
  int n_;
  // row-major, so that a row operation walks contiguous memory
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> t_;
  std::vector<int> nonzero_;     // columns of the pivot row that are not zero
  std::vector<int> basis_;
};

// z from the final basis: the basic z solve M_SS z_S = -q_S (the basis is
// nonsingular, hence so is M_SS, since det B = +-det M_SS).
void Polish(const MatX& M, const VecX& q, const std::vector<int>& basic_z, bool least_norm, VecX* z) {
  const int m = static_cast<int>(basic_z.size());
  if (m == 0) return;
  MatX Mss(m, m);
  VecX qs(m);
  for (int i = 0; i < m; ++i) {
    qs[i] = q[basic_z[i]];
    for (int j = 0; j < m; ++j) Mss(i, j) = M(basic_z[i], basic_z[j]);
  }
  // a regularised path ends with dependent rows basic: M_SS singular
  const VecX zs = least_norm ? VecX(Eigen::CompleteOrthogonalDecomposition<MatX>(Mss).solve(-qs))
                             : VecX(Eigen::PartialPivLU<MatX>(Mss).solve(-qs));
  if (!zs.allFinite()) return;
  VecX polished = VecX::Zero(z->size());
  for (int i = 0; i < m; ++i) polished[basic_z[i]] = zs[i];
  // keep the polished answer only when it is at least as good
  if (LcpError(M, q, polished) <= LcpError(M, q, *z)) *z = polished;
}

}  // namespace

LcpSolution SolveLemke(const MatX& M, const VecX& q, const LemkeOptions& options) {
  const int n = static_cast<int>(q.size());
  LcpSolution sol;
  sol.z = VecX::Zero(n);
  sol.w = q;
  if (n == 0 || q.minCoeff() >= 0.0) return sol;  // z = 0 solves it

  const double scale = std::max(1.0, M.cwiseAbs().maxCoeff());
  const double eps = options.pivot_tolerance * scale;
  const double tie = 1e-12;
  const int max_pivots = options.max_pivots > 0 ? options.max_pivots : 50 * (n + 1);
  Tableau t(options.regularization > 0.0 ? MatX(M + options.regularization * MatX::Identity(n, n)) : M, q);

  // first pivot: z0 enters in the row of the most negative q_i / d_i, which
  // makes every w_i >= 0 (lexicographic among ties, as in the main loop)
  int row = -1;
  for (int i = 0; i < n; ++i) {
    // the column is -d: the largest ratio is the most negative q_i / d_i
    if (row < 0 || t.CompareRatios(i, row, t.Artificial(), tie) > 0) row = i;
  }
  int leaving = t.Basic(row);
  t.Pivot(row, t.Artificial());
  sol.pivots = 1;

  while (true) {
    const int entering = t.Complement(leaving);
    // minimum-ratio test over rows whose entry in the entering column is positive
    row = -1;
    int z0_row = -1;
    for (int i = 0; i < n; ++i) {
      if (t.At(i, entering) <= eps) continue;
      if (t.Basic(i) == t.Artificial()) z0_row = i;
      if (row < 0 || t.CompareRatios(i, row, entering, tie) < 0) row = i;
    }
    if (z0_row >= 0 && t.RatioTied(z0_row, row, entering, tie)) row = z0_row;
    if (row < 0) {
      sol.outcome = LcpOutcome::kRayTermination;
      return sol;
    }
    if (sol.pivots >= max_pivots) {
      sol.outcome = LcpOutcome::kPivotLimit;
      return sol;
    }
    leaving = t.Basic(row);
    t.Pivot(row, entering);
    ++sol.pivots;
    if (leaving == t.Artificial()) break;
  }

  std::vector<int> basic_z;
  for (int i = 0; i < n; ++i) {
    const int var = t.Basic(i);
    if (var >= n && var < 2 * n) {
      sol.z[var - n] = std::max(0.0, t.At(i, t.Rhs()));
      basic_z.push_back(var - n);
    }
  }
  std::sort(basic_z.begin(), basic_z.end());
  Polish(M, q, basic_z, options.regularization > 0.0, &sol.z);
  sol.z = sol.z.cwiseMax(0.0);
  sol.w = M * sol.z + q;
  return sol;
}

}  // namespace contactsim
