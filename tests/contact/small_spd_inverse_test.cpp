// Tests of small_spd_inverse.h: the normal blocks' K^-1 is what Eigen's
// LLT of the block padded to 4 x 4 with the identity gave, bit for bit
// (so replacing it moved no trajectory), and a K that is not positive
// definite is refused.
#include "service/contact/small_spd_inverse.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cstring>

#include "tests/contact/seeded_draw.h"

namespace contactsim {
namespace {

// A random n x n J M^-1 J^T-like K (positive definite, of the scale of a
// box's normal rows), padded with the identity.
Eigen::Matrix4d RandomK(testing::Draw& draw, int n) {
  Eigen::Matrix<double, 4, 6> j = Eigen::Matrix<double, 4, 6>::Zero();
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 6; ++c) j(i, c) = draw.Uniform(-1.0, 1.0);
  }
  const double scale = draw.Uniform(1e-4, 1e1);
  Eigen::Matrix4d k = scale * (j * j.transpose());
  for (int i = 0; i < n; ++i) k(i, i) += scale * draw.Uniform(0.0, 1e-2);
  for (int i = n; i < 4; ++i) k(i, i) = 1.0;
  return k;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

TEST(SmallSpdInverseTest, GivesEigensLltInverseBitForBit) {
  testing::Draw draw(11);
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = 2 + trial % 3;
    const Eigen::Matrix4d k = RandomK(draw, n);
    const Eigen::LLT<Eigen::Matrix4d> llt(k);
    ASSERT_EQ(llt.info(), Eigen::Success);
    const Eigen::Matrix4d expected = llt.solve(Eigen::Matrix4d::Identity());
    Eigen::Matrix4d inv = Eigen::Matrix4d::Zero();
    double pivots[4];
    ASSERT_TRUE(SmallSpdInverse(k, n, &inv, pivots));
    for (int i = 0; i < n; ++i) {
      EXPECT_TRUE(SameBits(pivots[i], llt.matrixLLT()(i, i))) << "trial " << trial;
      for (int c = 0; c < n; ++c) {
        EXPECT_TRUE(SameBits(inv(i, c), expected(i, c))) << "trial " << trial << " (" << i << ", " << c << ")";
      }
    }
  }
}

TEST(SmallSpdInverseTest, ReadsOnlyTheLowerTriangle) {
  testing::Draw draw(12);
  const Eigen::Matrix4d k = RandomK(draw, 4);
  Eigen::Matrix4d lower = k;
  for (int i = 0; i < 4; ++i) {
    for (int c = i + 1; c < 4; ++c) lower(i, c) = 123.0;
  }
  Eigen::Matrix4d a, b;
  double pivots[4];
  ASSERT_TRUE(SmallSpdInverse(k, 4, &a, pivots));
  ASSERT_TRUE(SmallSpdInverse(lower, 4, &b, pivots));
  EXPECT_EQ(a, b);
}

TEST(SmallSpdInverseTest, RefusesAMatrixThatIsNotPositiveDefinite) {
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  k(1, 0) = k(0, 1) = 2.0;  // eigenvalues 3 and -1
  Eigen::Matrix4d inv = Eigen::Matrix4d::Zero();
  double pivots[4];
  EXPECT_FALSE(SmallSpdInverse(k, 2, &inv, pivots));
  EXPECT_FALSE(SmallSpdInverse(Eigen::Matrix4d::Zero(), 3, &inv, pivots));
}

}  // namespace
}  // namespace contactsim
