// Tests of the portable elementary functions against the C library (which
// is more accurate but not the same on every machine, portable_math.h):
// within a few ulp over the ranges the engine uses, and the IEEE 754
// special cases.
#include "service/physics/portable_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

namespace contactsim {
namespace {

using portable::Asin;
using portable::Atan2;
using portable::Cos;
using portable::Exp;
using portable::Log;
using portable::Pow;
using portable::Sin;

// Units in the last place between two finite doubles.
int64_t UlpDistance(double a, double b) {
  if (a == b) return 0;  // +0 and -0 too
  int64_t ia, ib;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  if (ia < 0) ia = std::numeric_limits<int64_t>::min() - ia;  // monotone in the value
  if (ib < 0) ib = std::numeric_limits<int64_t>::min() - ib;
  return ia > ib ? ia - ib : ib - ia;
}

// The worst distance over n arguments drawn uniformly from [lo, hi]
// (mt19937_64 is specified bit for bit by the standard; the mapping to
// [0, 1) is written out so that no library's distribution enters).
template <typename F, typename G>
int64_t WorstUlp(F ours, G reference, double lo, double hi, int n = 20000) {
  std::mt19937_64 rng(7);
  int64_t worst = 0;
  for (int i = 0; i < n; ++i) {
    const double u = (rng() >> 11) * (1.0 / 9007199254740992.0);
    const double x = lo + (hi - lo) * u;
    worst = std::max(worst, UlpDistance(ours(x), reference(x)));
  }
  return worst;
}

// 2 ulp: each function's error bound in portable_math.h; glibc is within
// one ulp, so a reduction or polynomial term gone wrong shows as thousands.
constexpr int64_t kUlp = 2;

// Verifies that sin and cos are within kUlp of the C library where the
// engine calls them (half angles of a step's rotation, random orientations
// in [0, 2 pi)) and beyond, up to 1e5 rad.
TEST(PortableMathTest, SinAndCosAreWithinTwoUlpOfTheCLibrary) {
  for (double hi : {0.7, 4.0, 7.0, 100.0, 1e5}) {
    EXPECT_LE(WorstUlp(Sin, [](double x) { return std::sin(x); }, -hi, hi), kUlp) << hi;
    EXPECT_LE(WorstUlp(Cos, [](double x) { return std::cos(x); }, -hi, hi), kUlp) << hi;
  }
  EXPECT_EQ(Sin(0.0), 0.0);
  EXPECT_EQ(Cos(0.0), 1.0);
  EXPECT_TRUE(std::isnan(Sin(std::numeric_limits<double>::infinity())));
}

// Verifies exp and log over their whole useful range and at the edges.
TEST(PortableMathTest, ExpAndLogAreWithinTwoUlpOfTheCLibrary) {
  EXPECT_LE(WorstUlp(Exp, [](double x) { return std::exp(x); }, -700.0, 700.0), kUlp);
  EXPECT_LE(WorstUlp(Exp, [](double x) { return std::exp(x); }, -1.0, 1.0), kUlp);
  EXPECT_LE(WorstUlp(Log, [](double x) { return std::log(x); }, 1e-300, 1e300), kUlp);
  EXPECT_LE(WorstUlp(Log, [](double x) { return std::log(x); }, 0.5, 2.0), kUlp);
  EXPECT_LE(WorstUlp(Log, [](double x) { return std::log(x); }, 1e-6, 1e-3), kUlp);  // barrier d / d_hat
  EXPECT_EQ(Exp(0.0), 1.0);
  EXPECT_EQ(Log(1.0), 0.0);
  EXPECT_EQ(Exp(710.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(Exp(-750.0), 0.0);
  EXPECT_EQ(Log(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(Log(-1.0)));
  EXPECT_LE(UlpDistance(Log(5e-324), std::log(5e-324)), kUlp);  // subnormal
}

// Verifies pow on the penalty method's Hunt-Crossley depths (m) and
// exponents: exp(y log x) loses |y log x| ulp, here at most about 20.
TEST(PortableMathTest, PowOfSmallDepthsIsWithinItsBound) {
  for (double y : {0.5, 1.5, 2.0}) {
    EXPECT_LE(WorstUlp([y](double x) { return Pow(x, y); }, [y](double x) { return std::pow(x, y); }, 1e-7, 0.1),
              32)
        << y;
  }
  EXPECT_EQ(Pow(0.0, 1.5), 0.0);
  EXPECT_EQ(Pow(2.0, 0.0), 1.0);
  EXPECT_TRUE(std::isnan(Pow(-1.0, 1.5)));
}

// Verifies atan2 in all four quadrants and asin on [-1, 1] (within 3 ulp).
TEST(PortableMathTest, Atan2AndAsinAreWithinTwoUlpOfTheCLibrary) {
  std::mt19937_64 rng(11);
  int64_t worst = 0;
  for (int i = 0; i < 20000; ++i) {
    const double y = ((rng() >> 11) * (1.0 / 9007199254740992.0) - 0.5) * 10.0;
    const double x = ((rng() >> 11) * (1.0 / 9007199254740992.0) - 0.5) * 10.0;
    worst = std::max(worst, UlpDistance(Atan2(y, x), std::atan2(y, x)));
  }
  EXPECT_LE(worst, kUlp);
  // asin x = atan2(x, sqrt((1 - x)(1 + x))) adds the rounding of the root
  EXPECT_LE(WorstUlp(Asin, [](double x) { return std::asin(x); }, -1.0, 1.0), kUlp + 1);
  EXPECT_EQ(Asin(1.0), std::asin(1.0));
  EXPECT_TRUE(std::isnan(Asin(1.5)));
}

// Verifies the IEEE 754 special cases of atan2 (signed zeros, infinities),
// which decide the sign of a hinge angle at the seam.
TEST(PortableMathTest, Atan2SpecialCasesMatchTheCLibraryExactly) {
  const double inf = std::numeric_limits<double>::infinity();
  for (double y : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
    for (double x : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
      const double ours = Atan2(y, x), theirs = std::atan2(y, x);
      EXPECT_EQ(ours, theirs) << "atan2(" << y << ", " << x << ")";
      EXPECT_EQ(std::signbit(ours), std::signbit(theirs)) << "atan2(" << y << ", " << x << ")";
    }
  }
}

}  // namespace
}  // namespace contactsim
