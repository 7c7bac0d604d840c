// The closed-form box-box separating-axis test against the general
// polyhedron test on the posed boxes (box_box_sat.h promises the same
// result up to round-off).
#include "service/collision/box_box_sat.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::RandomRotation;
using testing_util::RandomVector;

constexpr double kTol = 1e-12;  // m, round-off of ~1 m coordinates

void ExpectSameResult(const RigidBody& a, const RigidBody& b, double early_out, const char* what, int trial) {
  PosedPolyhedron pa, pb;
  ASSERT_TRUE(PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb));
  const SatResult general = FindSeparatingAxis(pa, pb, early_out);
  const SatResult boxes = FindBoxBoxSeparatingAxis(a, b, early_out);
  EXPECT_EQ(boxes.axis, general.axis) << what << " trial " << trial << " kinds " << int(boxes.axis.kind) << " "
                                      << int(general.axis.kind);
  EXPECT_NEAR(boxes.separation, general.separation, kTol) << what << " trial " << trial;
  EXPECT_NEAR((boxes.normal - general.normal).norm(), 0.0, 1e-9) << what << " trial " << trial;
  EXPECT_NEAR(boxes.max_separation, general.max_separation, kTol) << what << " trial " << trial;
}

// Verifies the same axis (kind and face or edge indices), separation,
// normal and unbiased maximum as FindSeparatingAxis on 2,000 random pairs
// of boxes of random sizes, overlapping, touching and apart, without an
// early out; and, with an early out, the same separating axis.
TEST(BoxBoxSat, MatchesTheGeneralTestOnRandomPairs) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> size(0.05, 0.6);
  for (int trial = 0; trial < 2000; ++trial) {
    const RigidBody a = Box(1, Vec3(size(rng), size(rng), size(rng)), RandomVector(rng, 0.3), RandomRotation(rng));
    const RigidBody b = Box(2, Vec3(size(rng), size(rng), size(rng)), RandomVector(rng, 1.2), RandomRotation(rng));
    ExpectSameResult(a, b, std::numeric_limits<double>::infinity(), "no early out", trial);
    ExpectSameResult(a, b, 0.01, "early out", trial);
  }
}

// Verifies the same choice for the resting pairs of a stack: unit boxes
// side by side and on top of each other, exactly aligned (where the
// general test keeps no edge pair) and turned by up to 1e-3 rad about
// random axes, with gaps and overlaps of up to 1 mm.
TEST(BoxBoxSat, MatchesTheGeneralTestOnNearlyAlignedStacks) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> tilt(-1e-3, 1e-3), gap(-1e-3, 1e-3);
  const Vec3 h(0.5, 0.5, 0.5);
  for (int trial = 0; trial < 600; ++trial) {
    const bool aligned = trial % 3 == 0;
    auto turn = [&]() {
      return aligned ? Quat::Identity() : Quat(Eigen::AngleAxisd(tilt(rng), RandomVector(rng, 1.0).normalized()));
    };
    const Vec3 offset = trial % 2 == 0 ? Vec3(0.5 + tilt(rng) * 100, 0, 1.0 + gap(rng))  // on top, half over
                                       : Vec3(1.0 + gap(rng), 0, 0);                      // side by side
    const RigidBody a = Box(1, h, Vec3::Zero(), turn());
    const RigidBody b = Box(2, h, offset, turn());
    ExpectSameResult(a, b, std::numeric_limits<double>::infinity(), "stack", trial);
    ExpectSameResult(a, b, 1e-3, "stack, early out", trial);
  }
}

}  // namespace
}  // namespace contactsim
