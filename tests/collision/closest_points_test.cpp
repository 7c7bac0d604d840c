#include "service/collision/closest_points.h"

#include <gtest/gtest.h>

#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

// Closed-form inputs are exact in binary up to a few ulps of 1 m.
using testing_util::kTol;

// Verifies that a point beyond a segment's end projects onto that end.
TEST(ClosestPointsTest, PointBeyondSegmentEndClampsToEnd) {
  double t = -1.0;
  const Vec3 c = ClosestPointOnSegment(Vec3(3, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0), &t);
  EXPECT_NEAR(t, 1.0, kTol);
  EXPECT_TRUE(c.isApprox(Vec3(2, 0, 0), kTol));
}

// Verifies that crossing skew segments meet at their hand-computed closest points.
TEST(ClosestPointsTest, SkewSegmentsGiveCommonPerpendicularFeet) {
  const SegmentClosestPoints cp =
      ClosestPointsOfSegments(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.5, -1, 2), Vec3(0.5, 1, 2));
  EXPECT_NEAR(cp.s, 0.75, kTol);
  EXPECT_NEAR(cp.t, 0.5, kTol);
  EXPECT_NEAR((cp.c1 - Vec3(0.5, 0, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((cp.c2 - Vec3(0.5, 0, 2)).norm(), 0.0, kTol);
}

// Verifies that parallel segments give a pair of points at their true distance.
TEST(ClosestPointsTest, ParallelSegmentsGiveTheirDistance) {
  const SegmentClosestPoints cp =
      ClosestPointsOfSegments(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 1), Vec3(3, 0, 1));
  EXPECT_NEAR((cp.c2 - cp.c1).norm(), 1.0, kTol);
}

// Verifies that degenerate segments (points) are handled.
TEST(ClosestPointsTest, DegenerateSegmentsArePoints) {
  const SegmentClosestPoints cp =
      ClosestPointsOfSegments(Vec3(0, 0, 0), Vec3(0, 0, 0), Vec3(1, -1, 0), Vec3(1, 1, 0));
  EXPECT_NEAR((cp.c2 - Vec3(1, 0, 0)).norm(), 0.0, kTol);
}

}  // namespace
}  // namespace contactsim
