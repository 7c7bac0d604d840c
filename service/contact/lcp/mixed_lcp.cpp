#include "service/contact/lcp/mixed_lcp.h"

#include <Eigen/QR>

namespace contactsim {
namespace {

MatX Gather(const MatX& A, const std::vector<int>& rows, const std::vector<int>& cols) {
  MatX out(rows.size(), cols.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    for (size_t j = 0; j < cols.size(); ++j) out(i, j) = A(rows[i], cols[j]);
  }
  return out;
}

VecX Gather(const VecX& b, const std::vector<int>& rows) {
  VecX out(rows.size());
  for (size_t i = 0; i < rows.size(); ++i) out[i] = b[rows[i]];
  return out;
}

}  // namespace

LcpSolution SolveMixedLcp(const MatX& A, const VecX& b, const std::vector<bool>& free,
                          const LemkeOptions& options) {
  std::vector<int> F, C;
  for (int i = 0; i < static_cast<int>(b.size()); ++i) (free[i] ? F : C).push_back(i);
  if (F.empty()) return SolveLemke(A, b, options);

  const MatX Aff = Gather(A, F, F), Afc = Gather(A, F, C), Acf = Gather(A, C, F), Acc = Gather(A, C, C);
  const VecX bf = Gather(b, F), bc = Gather(b, C);
  const Eigen::CompleteOrthogonalDecomposition<MatX> ff(Aff);
  // A_FF^+ A_FC; with no complementary rows (joints only) A_FC has no
  // columns, and Eigen's triangular solve would bind a reference to the
  // empty block's null data (UBSan), so it is not called
  const MatX X = C.empty() ? MatX(F.size(), 0) : MatX(ff.solve(Afc));
  const VecX y = ff.solve(bf);   // A_FF^+ b_F
  LcpSolution reduced = SolveLemke(Acc - Acf * X, bc - Acf * y, options);

  LcpSolution sol;
  sol.outcome = reduced.outcome;
  sol.pivots = reduced.pivots;
  sol.z = VecX::Zero(b.size());
  if (reduced.outcome != LcpOutcome::kSolved) {
    sol.w = b;
    return sol;
  }
  const VecX xf = -(X * reduced.z + y);
  if (!xf.allFinite()) {
    sol.outcome = LcpOutcome::kSingular;
    sol.w = b;
    return sol;
  }
  for (size_t i = 0; i < F.size(); ++i) sol.z[F[i]] = xf[i];
  for (size_t i = 0; i < C.size(); ++i) sol.z[C[i]] = reduced.z[i];
  sol.w = A * sol.z + b;
  return sol;
}

}  // namespace contactsim
