// Tests of the joint tree solver's dense kernels (contact/joints/small_lu.h):
// A x = b solved for a known x, at every size the tree's nodes take (the
// compile-time sizes and the others), with one right-hand side and several.
#include "service/contact/joints/small_lu.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace contactsim {
namespace {

// A (n x n, row-major) times x (n x m, row-major)
std::vector<double> Multiply(int n, int m, const std::vector<double>& a, const std::vector<double>& x) {
  std::vector<double> b(n * m, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < m; ++j) b[i * m + j] += a[i * n + k] * x[k * m + j];
    }
  }
  return b;
}

// Every size 1 to 24 and every width of the tree's solves: a random matrix
// with a dominant diagonal (well conditioned, a pivot search still needed
// on its off-diagonal rows) and a random known solution come back to round-off.
TEST(SmallLuTest, SolvesForAKnownAnswerAtEverySize) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int n = 1; n <= 24; ++n) {
    for (int m : {1, 5, 6, 7, 8, 3}) {
      std::vector<double> a(n * n), x(n * m);
      for (double& v : a) v = u(rng);
      for (int i = 0; i < n; ++i) a[i * n + i] += n * (i % 2 ? -1.0 : 1.0);  // indefinite, as a body with world joints
      for (double& v : x) v = u(rng);
      std::vector<double> b = Multiply(n, m, a, x);
      std::vector<int> pivots(n);
      LuFactor(n, a.data(), pivots.data());
      LuSolve(n, a.data(), pivots.data(), b.data(), m);
      for (int k = 0; k < n * m; ++k) EXPECT_NEAR(b[k], x[k], 1e-12) << "n " << n << " m " << m << " entry " << k;
    }
  }
}

// A zero on the diagonal (a saddle point's lower-right block before its
// rows are pivoted) needs the row exchange: [[0, 1], [1, 0]] x = (2, 3)
// gives x = (3, 2) exactly; a block of 6 with the same pattern, its answer
// the reversed right-hand side.
TEST(SmallLuTest, PivotsPastAZeroDiagonal) {
  for (int n : {2, 6, 9}) {
    std::vector<double> a(n * n, 0.0), b(n);
    for (int i = 0; i < n; ++i) {
      a[i * n + (n - 1 - i)] = 1.0;  // the exchange matrix: zero diagonal where n is even
      b[i] = i + 2.0;
    }
    std::vector<int> pivots(n);
    LuFactor(n, a.data(), pivots.data());
    LuSolve(n, a.data(), pivots.data(), b.data(), 1);
    for (int i = 0; i < n; ++i) EXPECT_EQ(b[i], n - 1 - i + 2.0) << "n " << n << " row " << i;
  }
}

}  // namespace
}  // namespace contactsim
