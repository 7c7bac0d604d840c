// The stacking test for the lcp method: a pyramid of 20 rows of
// unit boxes stands for 10 s.
#include <gtest/gtest.h>

#include <cstdio>

#include "service/contact/lcp/lcp_method.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;

// Verifies that a pyramid of 20 rows (210 unit boxes, a base of 20
// touching boxes, each row offset by half a box) stands for 10 s (2,400
// steps at 1/240 s) under pgs with warm starting and 10 sweeps per step
// (Bullet's default; it keeps the test at ~10 s), the top box moving less
// than 5 cm (the required bound) and no box falling off.
TEST(LcpPyramid, TwentyRowsStandTenSecondsWithPgs) {
  constexpr int kRows = 20;
  constexpr double kMaxTopDrift = 0.05;  // m
  World world;
  CollisionDetector detector;
  LcpMethod method;
  ASSERT_TRUE(method.SetParams({{"solver", "pgs"}, {"warm_start", "true"}, {"iterations", "10"}}).ok());
  AddGround(world, 0.0, 0.5);
  BodyId top = 0;
  for (int row = 0; row < kRows; ++row) {
    for (int i = 0; i < kRows - row; ++i) {
      top = AddBox(world, 0.5, Vec3(i + 0.5 * row, 0, 0.5 + row), 0.0, 0.5);
    }
  }
  ASSERT_EQ(world.bodies().size(), 211u);
  const Vec3 top0 = world.Find(top)->x;
  ContactSet contacts;
  int iterations = 0;
  double worst_drift = 0.0;
  for (int step = 0; step < 2400; ++step) {
    iterations += method.Step(world, detector, &contacts).iterations;
    worst_drift = std::max(worst_drift, (world.Find(top)->x - top0).norm());
  }
  double lowest_top_row = 1e9;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic()) lowest_top_row = std::min(lowest_top_row, b.x.z());
  }
  EXPECT_LT(worst_drift, kMaxTopDrift);
  EXPECT_GT(lowest_top_row, 0.45);  // every box still standing on something
  std::printf("pyramid: top box moved at most %.2e m in 10 s, %zu contacts, %.1f sweeps/step\n", worst_drift,
              contacts.size(), iterations / 2400.0);
}

}  // namespace
}  // namespace contactsim
