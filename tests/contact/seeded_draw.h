// Seeded random numbers for the tests that draw their scenes (random scenes,
// random convex hulls), the same on every compiler and library.
#pragma once

#include <random>

#include "service/physics/math.h"

namespace contactsim {
namespace testing {

// Random numbers from mt19937's raw output, which the standard fixes, each
// drawn in its own statement: the standard distributions are each
// library's own and the order of a call's arguments is each compiler's, so
// with them g++ and clang built different scenes from one seed.
class Draw {
 public:
  explicit Draw(unsigned seed) : rng_(seed) {}
  double Uniform(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(rng_()) / 4294967296.0); }
  int Index(int n) { return static_cast<int>(rng_() % static_cast<unsigned>(n)); }
  Vec3 Vector(double lo, double hi) {
    const double x = Uniform(lo, hi);
    const double y = Uniform(lo, hi);
    const double z = Uniform(lo, hi);
    return Vec3(x, y, z);
  }

 private:
  std::mt19937 rng_;
};

}  // namespace testing
}  // namespace contactsim
