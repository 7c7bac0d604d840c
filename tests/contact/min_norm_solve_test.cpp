// MinNormSolve (min_norm_solve.h) against the dense minimum-norm
// least-squares answer, S^+ b, on matrices built as the direct solve builds
// them: J J^T scaled to unit diagonal, singular where rows are dependent.
#include "service/contact/min_norm_solve.h"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <Eigen/SVD>
#include <random>

namespace contactsim {
namespace {

// A rank-`rank` unit-diagonal J J^T of size n, J n x rank with random
// entries; `weak` of its columns are scaled by `weak_scale`, which gives S
// eigenvalues of about weak_scale^2 (nearly dependent rows).
Eigen::MatrixXd UnitDiagonalGram(int n, int rank, int weak, double weak_scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd J(n, rank);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < rank; ++j) J(i, j) = normal(rng);
  }
  J.rightCols(weak) *= weak_scale;
  Eigen::MatrixXd S = J * J.transpose();
  const Eigen::VectorXd d = S.diagonal().cwiseSqrt().cwiseInverse();
  return d.asDiagonal() * S * d.asDiagonal();
}

Eigen::VectorXd Random(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = normal(rng);
  return v;
}

Eigen::VectorXd DenseMinNorm(const Eigen::MatrixXd& S, const Eigen::VectorXd& b) {
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(S).solve(b);
}

TEST(MinNormSolveTest, FullRankSolvesWithTheSparseFactor) {
  for (int n : {1, 5, 40}) {
    const Eigen::MatrixXd S = UnitDiagonalGram(n, n + 3, 0, 1.0, 7 + n);
    const Eigen::VectorXd b = Random(n, 11 + n);
    MinNormReport report;
    const Eigen::VectorXd y = MinNormSolve(S.sparseView(), b, &report);
    EXPECT_FALSE(report.fallback) << n;
    EXPECT_LE((S * y - b).norm(), 1e-10 * b.norm()) << n;
  }
}

// S = Q diag(lambda) Q^T with Q a random rotation of R^n: its spectrum as
// given, zeros for dependent rows.
Eigen::MatrixXd WithSpectrum(const Eigen::VectorXd& lambda, unsigned seed) {
  const int n = static_cast<int>(lambda.size());
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(UnitDiagonalGram(n, n, 0, 1.0, seed)
                                                                       + Eigen::MatrixXd::Identity(n, n))
                                .householderQ();
  return Q * lambda.asDiagonal() * Q.transpose();
}

// Dependent rows (a face's coplanar points): b in S's range is met and y
// has no part in S's null space, the minimum-norm answer. The part of b
// that rounding leaves in the null space (about 1e-16 |b|) reaches y
// divided by the regularisation, so y agrees with S^+ b to about 1e-16 /
// 1e-8 relative, not to the last digit.
TEST(MinNormSolveTest, SingularConsistentGivesTheMinimumNorm) {
  for (int rank : {3, 10, 25}) {
    const int n = 30;
    const Eigen::MatrixXd S = UnitDiagonalGram(n, rank, 0, 1.0, 100 + rank);
    const Eigen::VectorXd b = S * Random(n, 200 + rank);
    MinNormReport report;
    const Eigen::VectorXd y = MinNormSolve(S.sparseView(), b, &report);
    EXPECT_FALSE(report.fallback) << rank;
    EXPECT_LE((S * y - b).norm(), 1e-10 * b.norm()) << rank;
    EXPECT_LE((y - DenseMinNorm(S, b)).norm(), 1e-5 * y.norm()) << rank;
  }
}

// Nearly dependent rows, smallest non-zero eigenvalues 2e-8 to 1e-6 (an
// arm's joint rows with contacts on its links), beside exact zeros: two
// refinements leave the residual far above 1e-10, since each shrinks the
// error along such an eigenvector only by eps / (sigma + eps); more reach
// it, and the dense decomposition is not needed. The answer along the
// weakest direction is as good as the residual makes it: within
// 1e-10 |b| / sigma of S^+ b.
TEST(MinNormSolveTest, NearlySingularConsistentRefinesWithoutTheDenseFallback) {
  for (double weak : {2e-8, 1e-7, 1e-6}) {
    for (unsigned seed : {1u, 2u, 3u}) {
      const int n = 40;
      Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(n, 0.1, 2.0);
      lambda.head(3) << weak, 3.0 * weak, 0.0;
      lambda(3) = 0.0;
      const Eigen::MatrixXd S = WithSpectrum(lambda, seed);
      const Eigen::VectorXd b = S * Random(n, seed + 50);
      MinNormReport report;
      const Eigen::VectorXd y = MinNormSolve(S.sparseView(), b, &report);
      EXPECT_FALSE(report.fallback) << weak << " " << seed;
      EXPECT_LE((S * y - b).norm(), 1e-10 * b.norm()) << weak << " " << seed;
      const double forward = 1e-10 * b.norm() / weak + 1e-5 * y.norm();
      EXPECT_LE((y - DenseMinNorm(S, b)).norm(), forward) << weak << " " << seed;
    }
  }
}

// Targets no impulses can meet (b with a part in S's null space): the
// least-squares minimum-norm answer, from the dense decomposition.
TEST(MinNormSolveTest, InconsistentTargetsGetTheLeastSquaresAnswer) {
  const int n = 20;
  const Eigen::MatrixXd S = UnitDiagonalGram(n, 12, 0, 1.0, 5);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(S, Eigen::ComputeFullU);
  const Eigen::VectorXd null_part = svd.matrixU().col(n - 1);
  const Eigen::VectorXd b = S * Random(n, 6) + 0.3 * null_part;
  MinNormReport report;
  const Eigen::VectorXd y = MinNormSolve(S.sparseView(), b, &report);
  EXPECT_TRUE(report.fallback);
  EXPECT_LE((y - DenseMinNorm(S, b)).norm(), 1e-9 * y.norm());
}

TEST(MinNormSolveTest, ZeroTargetsGiveZero) {
  const Eigen::MatrixXd S = UnitDiagonalGram(8, 5, 0, 1.0, 9);
  MinNormReport report;
  const Eigen::VectorXd y = MinNormSolve(S.sparseView(), Eigen::VectorXd::Zero(8), &report);
  EXPECT_FALSE(report.fallback);
  EXPECT_EQ(y.norm(), 0.0);
}

// The cache keeps symbolic analyses only: with it, every answer is the one
// without it bit for bit, however the patterns alternate (more patterns
// than it holds, each coming back).
TEST(MinNormSolveTest, CachedAnalysisGivesTheSameBits) {
  MinNormCache cache;
  for (int round = 0; round < 3; ++round) {
    for (int n = 2; n < 60; n += 1) {
      Eigen::MatrixXd S = UnitDiagonalGram(n, n / 2 + 1, 1, 1e-3, 300 + n);
      for (int i = 0; i < n; ++i) {  // a sparser pattern of its own for each n
        for (int j = 0; j < n; ++j) {
          if (i != j && (i + j) % (n % 5 + 2) == 0) S(i, j) = 0.0;
        }
      }
      S += 0.5 * Eigen::MatrixXd::Identity(n, n);  // still positive definite after the cuts
      const Eigen::VectorXd b = Random(n, 400 + n + round);
      const Eigen::SparseMatrix<double> sparse = S.sparseView();
      const Eigen::VectorXd plain = MinNormSolve(sparse, b);
      const Eigen::VectorXd cached = MinNormSolve(sparse, b, nullptr, &cache);
      ASSERT_EQ(plain.size(), cached.size());
      for (int i = 0; i < n; ++i) ASSERT_EQ(plain(i), cached(i)) << "n " << n << " round " << round;
    }
  }
}

}  // namespace
}  // namespace contactsim
