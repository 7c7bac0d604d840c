// Tests of the 3 x 3 LU solve against Eigen's PartialPivLU, bit for bit.
#include "service/physics/lu3.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cstring>
#include <random>

namespace contactsim {
namespace {

bool SameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }

// Verifies that SolveLu3 gives Eigen's answer to the last bit on random
// systems of every pivot order: dense matrices with entries of mixed signs
// and scales (every row swap occurs), and the integrator's own systems
// I + (h/2) [w]x over rates from 1e-3 to 1e5 rad/s (off the diagonal
// pivoting only above about 480 rad/s at h = 1/240 s).
TEST(SolveLu3, MatchesEigensPartialPivotingBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-3.0, 5.0);
  int swapped = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    Mat3 a;
    if (trial % 2 == 0) {
      for (int k = 0; k < 9; ++k) a(k / 3, k % 3) = unit(rng) * std::pow(10.0, exponent(rng) - 1.0);
    } else {
      const Vec3 w = Vec3(unit(rng), unit(rng), unit(rng)) * std::pow(10.0, exponent(rng));
      a = Mat3::Identity() + 0.5 / 240.0 * Skew(w);
    }
    const Vec3 b(unit(rng), unit(rng), unit(rng));
    const Eigen::PartialPivLU<Mat3> lu(a);
    swapped += lu.permutationP().indices() != Eigen::Vector3i(0, 1, 2);
    const Vec3 expected = lu.solve(b);
    const Vec3 got = SolveLu3(a, b);
    ASSERT_TRUE(SameBits(got, expected)) << "trial " << trial << "\nA =\n" << a << "\nb = " << b.transpose()
                                         << "\nEigen " << expected.transpose() << "\nSolveLu3 " << got.transpose();
  }
  EXPECT_GT(swapped, 50000);  // the pivoting paths were taken
}

// Verifies the solve on a system with a known answer: A x = b for a
// permutation-heavy A whose first pivot is its last row.
TEST(SolveLu3, SolvesAKnownSystem) {
  Mat3 a;
  a << 0.0, 2.0, 1.0, 1.0, 0.0, 3.0, 4.0, 1.0, 0.0;
  const Vec3 x(1.0, -2.0, 0.5);
  const Vec3 got = SolveLu3(a, a * x);
  EXPECT_NEAR((got - x).norm(), 0.0, 1e-14);
}

}  // namespace
}  // namespace contactsim
