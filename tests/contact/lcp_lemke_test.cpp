// Tests of Lemke's method and the mixed LCP against brute-force enumeration
// of all 2^n complementary bases.
#include "service/contact/lcp/lemke.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <random>

#include "service/contact/lcp/mixed_lcp.h"

namespace contactsim {
namespace {

// Round-off of an n <= 8 solve with entries O(1) is ~1e-14; 1e-9 is the
// agreement the issue asks for.
constexpr double kTol = 1e-9;

// Every complementary basis S (z_S basic, w_rest basic): solve
// M_SS z_S = -q_S and keep the first with z >= 0 and w >= 0. Returns false
// when no basis is feasible.
bool BruteForce(const MatX& M, const VecX& q, VecX* z_out) {
  const int n = static_cast<int>(q.size());
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> S;
    for (int i = 0; i < n; ++i) {
      if (mask & (1 << i)) S.push_back(i);
    }
    VecX z = VecX::Zero(n);
    if (!S.empty()) {
      const int m = static_cast<int>(S.size());
      MatX Mss(m, m);
      VecX qs(m);
      for (int i = 0; i < m; ++i) {
        qs[i] = q[S[i]];
        for (int j = 0; j < m; ++j) Mss(i, j) = M(S[i], S[j]);
      }
      Eigen::FullPivLU<MatX> lu(Mss);
      if (!lu.isInvertible()) continue;
      const VecX zs = lu.solve(-qs);
      for (int i = 0; i < m; ++i) z[S[i]] = zs[i];
    }
    const VecX w = M * z + q;
    if (z.minCoeff() >= -1e-12 && w.minCoeff() >= -1e-12) {
      *z_out = z;
      return true;
    }
  }
  return false;
}

// M = A A^T + delta I: positive definite for delta > 0; with A of rank r < n
// and delta = 0, positive semi-definite and singular.
MatX RandomSymmetric(std::mt19937& rng, int n, int rank, double delta) {
  std::normal_distribution<double> normal;
  MatX A(n, rank);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < rank; ++j) A(i, j) = normal(rng);
  }
  return A * A.transpose() + delta * MatX::Identity(n, n);
}

// q = w* - M z* for a complementary pair (z*, w*), so a solution exists;
// about a fifth of the indices have z*_i = w*_i = 0 (degenerate).
VecX SolvableQ(std::mt19937& rng, const MatX& M) {
  const int n = static_cast<int>(M.rows());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VecX z = VecX::Zero(n), w = VecX::Zero(n);
  for (int i = 0; i < n; ++i) {
    const double r = u(rng);
    if (r < 0.4) {
      z[i] = u(rng) + 0.1;
    } else if (r < 0.8) {
      w[i] = u(rng) + 0.1;
    }
  }
  return w - M * z;
}

struct Case {
  const char* name;
  bool definite;
};

class LemkeVsBruteForce : public ::testing::TestWithParam<Case> {};

// Verifies that Lemke's answer is the brute-force one: the same z (positive
// definite M: the solution is unique) or the same w (semi-definite M: for a
// symmetric PSD M the LCP is a convex QP, so M z and w are unique while z
// may not be), and that it solves the LCP to 1e-9, on 400 random problems
// of n = 1..8.
TEST_P(LemkeVsBruteForce, AgreesOnRandomProblems) {
  std::mt19937 rng(GetParam().definite ? 11 : 12);
  double worst = 0.0;
  int max_pivots = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + trial % 8;
    const MatX M = GetParam().definite ? RandomSymmetric(rng, n, n, 0.1)
                                       : RandomSymmetric(rng, n, std::max(1, n - 1 - trial % 3), 0.0);
    const VecX q = SolvableQ(rng, M);
    VecX z_ref;
    ASSERT_TRUE(BruteForce(M, q, &z_ref)) << "trial " << trial;
    const LcpSolution sol = SolveLemke(M, q);
    ASSERT_EQ(sol.outcome, LcpOutcome::kSolved) << "trial " << trial << " n " << n;
    EXPECT_LT(LcpError(M, q, sol.z), kTol) << "trial " << trial;
    const VecX w_ref = M * z_ref + q;
    const double err = GetParam().definite ? (sol.z - z_ref).cwiseAbs().maxCoeff()
                                           : (sol.w - w_ref).cwiseAbs().maxCoeff();
    EXPECT_LT(err, kTol) << "trial " << trial << " n " << n;
    worst = std::max(worst, err);
    max_pivots = std::max(max_pivots, sol.pivots);
  }
  std::printf("%s: largest difference from brute force %.2e, most pivots %d\n", GetParam().name, worst,
              max_pivots);
}

INSTANTIATE_TEST_SUITE_P(Matrices, LemkeVsBruteForce,
                         ::testing::Values(Case{"positive definite", true}, Case{"semi-definite", false}),
                         [](const auto& info) { return std::string(info.param.definite ? "Definite" : "SemiDefinite"); });

// Verifies that q >= 0 needs no pivot: z = 0.
TEST(Lemke, NonNegativeQGivesZeroWithoutPivots) {
  const MatX M = MatX::Identity(3, 3);
  const VecX q = VecX::Constant(3, 0.5);
  const LcpSolution sol = SolveLemke(M, q);
  EXPECT_EQ(sol.outcome, LcpOutcome::kSolved);
  EXPECT_EQ(sol.pivots, 0);
  EXPECT_EQ(sol.z.norm(), 0.0);
}

// Verifies the regularised pivots on dependent rows: the four corners
// (+-1, +-1) of a face of a body of unit mass and inertia approaching at
// 1 m/s, M = J J^T with J_i = (1, y_i, -x_i) (rank three): z solves it
// when J^T z = (1, 0, 0), a line along the corners' dependency (+ - + -),
// whose least-norm point loads each corner with 1/4, which the
// regularised path and its least-norm polish give to round-off, with
// w = M z + q = 0. Lemke without it also solves (w = 0) at some vertex.
TEST(Lemke, RegularisedPivotsGiveTheLeastNormSplitOfDependentRows) {
  MatX J(4, 3);
  const double corners[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; ++i) J.row(i) << 1.0, corners[i][1], -corners[i][0];
  const MatX M = J * J.transpose();
  const VecX q = VecX::Constant(4, -1.0);
  for (const double eps : {0.0, 1e-9}) {
    LemkeOptions options;
    options.regularization = eps;
    const LcpSolution sol = SolveLemke(M, q, options);
    ASSERT_EQ(sol.outcome, LcpOutcome::kSolved) << "eps " << eps;
    EXPECT_LT((M * sol.z + q).cwiseAbs().maxCoeff(), 1e-12) << "eps " << eps;
    std::printf("eps %g: z %.6f %.6f %.6f %.6f\n", eps, sol.z[0], sol.z[1], sol.z[2], sol.z[3]);
    if (eps > 0.0) {
      for (int i = 0; i < 4; ++i) EXPECT_NEAR(sol.z[i], 0.25, 1e-12) << "corner " << i;
    }
  }
}

// Verifies the failure status: M = -I, q = -1 has no solution (w = -z - 1 < 0)
// and Lemke ends on a secondary ray.
TEST(Lemke, InfeasibleProblemEndsOnARay) {
  const MatX M = -MatX::Identity(2, 2);
  const VecX q = VecX::Constant(2, -1.0);
  EXPECT_EQ(SolveLemke(M, q).outcome, LcpOutcome::kRayTermination);
}

// Verifies the pivot cap: a cap of one pivot stops a problem that needs more.
TEST(Lemke, PivotCapStopsWithItsOwnStatus) {
  std::mt19937 rng(3);
  const MatX M = RandomSymmetric(rng, 6, 6, 0.1);
  const VecX q = -VecX::Constant(6, 1.0);
  LemkeOptions options;
  options.max_pivots = 1;
  EXPECT_EQ(SolveLemke(M, q, options).outcome, LcpOutcome::kPivotLimit);
}

// Verifies the mixed LCP: with equality rows eliminated by the Schur
// complement, w_F = 0 exactly, the complementary rows solve their LCP, and
// the answer matches brute force on the full system in which the free
// variables are split as x = x+ - x- (an equivalent standard LCP).
TEST(MixedLcp, MatchesBruteForceOnTheEquivalentSplitProblem) {
  std::mt19937 rng(5);
  double worst = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 2 + trial % 5;
    const MatX A = RandomSymmetric(rng, n, n, 0.2);
    const VecX b = SolvableQ(rng, A);
    std::vector<bool> free(n, false);
    free[0] = true;
    if (n > 3) free[2] = true;
    const LcpSolution sol = SolveMixedLcp(A, b, free);
    ASSERT_EQ(sol.outcome, LcpOutcome::kSolved);
    for (int i = 0; i < n; ++i) {
      if (free[i]) {
        EXPECT_NEAR(sol.w[i], 0.0, kTol);
      } else {
        EXPECT_GT(sol.z[i], -kTol);
        EXPECT_GT(sol.w[i], -kTol);
        EXPECT_NEAR(sol.z[i] * sol.w[i], 0.0, kTol);
      }
    }
    // reference: free x_i = x+_i - x-_i with w+ = row_i, w- = -row_i, both >= 0 and complementary
    std::vector<int> F;
    for (int i = 0; i < n; ++i) {
      if (free[i]) F.push_back(i);
    }
    const int m = n + static_cast<int>(F.size());
    MatX M = MatX::Zero(m, m);
    VecX q = VecX::Zero(m);
    M.topLeftCorner(n, n) = A;
    q.head(n) = b;
    for (size_t k = 0; k < F.size(); ++k) {
      const int extra = n + static_cast<int>(k);
      M.col(extra).head(n) = -A.col(F[k]);
      M.row(extra).head(n) = -A.row(F[k]);
      q[extra] = -b[F[k]];
      for (size_t k2 = 0; k2 < F.size(); ++k2) M(extra, n + static_cast<int>(k2)) = A(F[k], F[k2]);
    }
    VecX z_ref;
    ASSERT_TRUE(BruteForce(M, q, &z_ref));
    VecX x_ref = z_ref.head(n);
    for (size_t k = 0; k < F.size(); ++k) x_ref[F[k]] -= z_ref[n + k];
    worst = std::max(worst, (sol.z - x_ref).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, kTol);
  std::printf("mixed LCP: largest difference from brute force %.2e\n", worst);
}

}  // namespace
}  // namespace contactsim
