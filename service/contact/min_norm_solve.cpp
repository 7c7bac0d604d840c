#include "service/contact/min_norm_solve.h"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>

namespace contactsim {
namespace {

constexpr double kRegularisation = 1e-8;  // relative to S's unit diagonal
constexpr double kResidual = 1e-10;       // accepted |S y - b| / |b|
constexpr int kRefinements = 2;

}  // namespace

Eigen::VectorXd MinNormSolve(const Eigen::SparseMatrix<double>& S, const Eigen::VectorXd& b,
                             MinNormReport* report) {
  Eigen::SparseMatrix<double> R = S;
  for (int i = 0; i < R.rows(); ++i) R.coeffRef(i, i) += kRegularisation;
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(R);
  if (llt.info() == Eigen::Success) {
    Eigen::VectorXd y = llt.solve(b);
    for (int step = 0; step < kRefinements; ++step) y += llt.solve(b - S * y);
    if ((S * y - b).norm() <= kResidual * b.norm()) return y;
  }
  if (report) report->fallback = true;
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Eigen::MatrixXd(S)).solve(b);
}

}  // namespace contactsim
