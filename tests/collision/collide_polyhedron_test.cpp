// Box and hull pairs: the vertex closed form against planes, and the
// separating-axis manifolds (face clipping, edge-edge) against each other.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "service/collision/narrowphase.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Convex;
using testing_util::Ground;
using testing_util::Hull;
using testing_util::MaxDepth;
using testing_util::RockHull;

// Poses built from short decimals and 45-degree rotations: results agree with
// the hand values to round-off, a few ulps of 1 m.
constexpr double kManifoldTol = 1e-9;  // m

// True if some contact lies at `point` (within kManifoldTol).
bool HasPoint(const ContactSet& contacts, const Vec3& point) {
  return std::any_of(contacts.begin(), contacts.end(),
                     [&](const Contact& c) { return (c.point - point).norm() < kManifoldTol; });
}

// Verifies that a box resting flat on the ground gives its four bottom corners with the right depth.
TEST(CollidePolyhedronTest, BoxRestingFlatOnPlaneGivesFourCorners) {
  ContactSet out;
  ASSERT_EQ(Collide(Box(1, Vec3(0.5, 0.3, 0.2), Vec3(0, 0, 0.19)), 0, Ground(2), 1, 0.0, &out), 4);
  for (const Contact& c : out) {
    EXPECT_NEAR(c.depth, 0.01, kManifoldTol);
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kManifoldTol);
  }
  for (double sx : {-0.5, 0.5}) {
    for (double sy : {-0.3, 0.3}) EXPECT_TRUE(HasPoint(out, Vec3(sx, sy, -0.005)));
  }
}

// Verifies that a box hovering within the margin gives four speculative corners with depth = -gap.
TEST(CollidePolyhedronTest, BoxAbovePlaneWithinMarginIsSpeculative) {
  ContactSet out;
  ASSERT_EQ(Collide(Box(1, Vec3(0.5, 0.3, 0.2), Vec3(0, 0, 0.23)), 0, Ground(2), 1, 0.05, &out), 4);
  for (const Contact& c : out) EXPECT_NEAR(c.depth, -0.03, kManifoldTol);
  out.clear();
  EXPECT_EQ(Collide(Box(1, Vec3(0.5, 0.3, 0.2), Vec3(0, 0, 0.23)), 0, Ground(2), 1, 0.02, &out), 0);
}

// Verifies that a box tilted about x touches the ground along one edge: two points.
TEST(CollidePolyhedronTest, TiltedBoxOnPlaneGivesItsLowEdge) {
  const double angle = 0.2;
  const Quat q(Eigen::AngleAxisd(angle, Vec3::UnitX()));
  // lowest corner height: centre z - (0.3 sin + 0.2 cos)
  const double low = 0.3 * std::sin(angle) + 0.2 * std::cos(angle);
  ContactSet out;
  ASSERT_EQ(Collide(Box(1, Vec3(0.5, 0.3, 0.2), Vec3(0, 0, low - 0.01), q), 0, Ground(2), 1, 0.0, &out), 2);
  for (const Contact& c : out) EXPECT_NEAR(c.depth, 0.01, kManifoldTol);
}

// Verifies that a small box on a large one gives four points at its bottom corners (face contact).
TEST(CollidePolyhedronTest, BoxOnBoxFaceContactGivesFourPoints) {
  const RigidBody base = Box(1, Vec3(1, 1, 0.5), Vec3::Zero());
  const RigidBody top = Box(2, Vec3(0.2, 0.3, 0.1), Vec3(0, 0, 0.58));
  ContactSet out;
  ASSERT_EQ(Collide(base, 0, top, 1, 0.0, &out), 4);
  for (const Contact& c : out) {
    EXPECT_NEAR(c.depth, 0.02, kManifoldTol);
    EXPECT_NEAR((c.normal - Vec3(0, 0, 1)).norm(), 0.0, kManifoldTol);
  }
  for (double sx : {-0.2, 0.2}) {
    for (double sy : {-0.3, 0.3}) EXPECT_TRUE(HasPoint(out, Vec3(sx, sy, 0.49)));
  }
}

// Verifies that clipping makes points where the incident face crosses the reference face's sides.
TEST(CollidePolyhedronTest, OffsetCubesClipToTheirOverlapSquare) {
  const RigidBody a = Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero());
  const RigidBody b = Box(2, Vec3(0.5, 0.5, 0.5), Vec3(0.5, 0.5, 0.99));
  ContactSet out;
  ASSERT_EQ(Collide(a, 0, b, 1, 0.0, &out), 4);
  for (const Vec3& p : {Vec3(0, 0, 0.495), Vec3(0.5, 0, 0.495), Vec3(0.5, 0.5, 0.495), Vec3(0, 0.5, 0.495)}) {
    EXPECT_TRUE(HasPoint(out, p)) << p.transpose();
  }
  for (const Contact& c : out) EXPECT_NEAR(c.depth, 0.01, kManifoldTol);
}

// Verifies that two equal cubes stacked flush give their four corners, at
// every size and height of a stack and with the upper one turned by a
// round-off: each edge of the incident face lies on a side plane of the
// reference face, its ends a round-off either side, and cutting it there
// once put a point anywhere along the edge (104 of these cases failed;
// docs/physics.md, "Why stacks leaned").
TEST(CollidePolyhedronTest, FlushEqualCubesGiveTheirFourCorners) {
  int pairs = 0;
  for (const double half : {0.02, 0.035, 0.05, 0.1, 0.15}) {
    for (int layer = 0; layer < 20; ++layer) {
      for (const double turn : {0.0, 3e-16, -1e-15, 4e-15}) {  // rad, about an axis near z
        const double z = half * (1 + 2 * layer);
        const Quat q(Eigen::AngleAxisd(turn, Vec3(0.1, 0.2, 1.0).normalized()));
        const RigidBody a = Box(1, Vec3(half, half, half), Vec3(0, 0, z));
        const RigidBody b = Box(2, Vec3(half, half, half), Vec3(0.0, 0.0, z + 2 * half - 1e-6), q);
        ContactSet out;
        const std::string where = "half " + std::to_string(half) + " layer " + std::to_string(layer);
        ASSERT_EQ(Collide(a, 0, b, 1, 0.0, &out), 4) << where << " turn " << turn;
        for (const Contact& c : out) {
          EXPECT_NEAR(std::abs(c.point.x()), half, kManifoldTol) << where << " turn " << turn;
          EXPECT_NEAR(std::abs(c.point.y()), half, kManifoldTol) << where << " turn " << turn;
        }
        ++pairs;
      }
    }
  }
  EXPECT_EQ(pairs, 400);
}

// Verifies that two boxes meeting edge to edge (crossed at right angles) give one point.
TEST(CollidePolyhedronTest, CrossedEdgesGiveOnePoint) {
  const double r2 = std::sqrt(2.0);
  const RigidBody a = Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero(), Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())));
  const RigidBody b = Box(2, Vec3(0.5, 0.5, 0.5), Vec3(0, 0, r2 - 0.01),
                          Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY())));
  ContactSet out;
  ASSERT_EQ(Collide(a, 0, b, 1, 0.0, &out), 1);
  EXPECT_NEAR(out[0].depth, 0.01, kManifoldTol);
  EXPECT_NEAR((out[0].normal - Vec3(0, 0, 1)).norm(), 0.0, kManifoldTol);
  EXPECT_NEAR((out[0].point - Vec3(0, 0, r2 / 2 - 0.005)).norm(), 0.0, kManifoldTol);
}

// Verifies that feature ids are stable under a small motion that keeps the same features.
TEST(CollidePolyhedronTest, FeatureIdsAreStableUnderSmallMotion) {
  const RigidBody base = Box(1, Vec3(1, 1, 0.5), Vec3::Zero());
  ContactSet before, after;
  Collide(base, 0, Box(2, Vec3(0.2, 0.3, 0.1), Vec3(0, 0, 0.58)), 1, 0.0, &before);
  Collide(base, 0, Box(2, Vec3(0.2, 0.3, 0.1), Vec3(0.01, -0.02, 0.585), Quat(Eigen::AngleAxisd(0.05, Vec3::UnitZ()))), 1,
          0.0, &after);
  ASSERT_EQ(before.size(), 4u);
  ASSERT_EQ(after.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(before[i].feature_id, after[i].feature_id);
  // and the ids of one manifold are distinct
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = i + 1; j < 4; ++j) EXPECT_NE(before[i].feature_id, before[j].feature_id);
  }
}

// Verifies convex-plane: a cube hull resting on the ground gives the four corners like a box.
TEST(CollidePolyhedronTest, CubeHullOnPlaneGivesFourCorners) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  ContactSet out;
  ASSERT_EQ(Collide(Convex(1, Hull(corners), Vec3(0, 0, 0.48)), 0, Ground(2), 1, 0.0, &out), 4);
  for (const Contact& c : out) EXPECT_NEAR(c.depth, 0.02, kManifoldTol);
}

// Verifies convex-plane on an irregular hull: the deepest contact is the lowest vertex.
TEST(CollidePolyhedronTest, RockOnPlaneDeepestContactIsLowestVertex) {
  const auto hull = RockHull();
  const Quat q(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  double lowest = 1e300;
  for (const Vec3& v : hull->vertices) lowest = std::min(lowest, (q * v).z());
  ContactSet out;
  ASSERT_GE(Collide(Convex(1, hull, Vec3(0, 0, -lowest - 0.015), q), 0, Ground(2), 1, 0.0, &out), 1);
  EXPECT_NEAR(MaxDepth(out), 0.015, kManifoldTol);
}

// Verifies convex-convex between two cube hulls agrees with box-box.
TEST(CollidePolyhedronTest, CubeHullsAgreeWithBoxes) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  const auto cube = Hull(corners);
  const Quat q(Eigen::AngleAxisd(0.3, Vec3(0.2, 0.1, 1).normalized()));
  const Vec3 x(0.3, 0.2, 0.95);
  ContactSet hulls, boxes;
  Collide(Convex(1, cube, Vec3::Zero()), 0, Convex(2, cube, x, q), 1, 0.0, &hulls);
  Collide(Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), 0, Box(2, Vec3(0.5, 0.5, 0.5), x, q), 1, 0.0, &boxes);
  ASSERT_FALSE(boxes.empty());
  ASSERT_EQ(hulls.size(), boxes.size());
  EXPECT_NEAR(MaxDepth(hulls), MaxDepth(boxes), kManifoldTol);
  for (size_t i = 0; i < boxes.size(); ++i) {
    EXPECT_NEAR((hulls[i].normal - boxes[i].normal).norm(), 0.0, kManifoldTol);
  }
}

// Verifies a long plank lying across a short support, tilted by round-off
// to 1e-4 rad, both bodies in either order: every contact lies on the
// support's top face, where the two touch. The plank's far end dips below
// the support's top plane beside the support, and the separating-axis depth
// along that face normal is the far end's; a point put there (the deepest
// vertex) gave a light support a lever arm of the plank's length.
TEST(CollidePolyhedronTest, PlankOverAShortSupportTouchesOnlyOverIt) {
  int pairs = 0;
  for (const double half : {0.05, 0.15}) {           // m, the support's half width
    for (const double length : {0.5, 1.0, 3.0}) {      // m, the plank's half length
      for (const double tilt : {1e-7, 1e-5, -1e-5, 1e-4}) {  // rad about y: the far end dips
        for (const bool support_first : {true, false}) {
          const RigidBody support = Box(support_first ? 1 : 2, Vec3(half, half, 0.05), Vec3(0, 0, 0.05));
          // the plank's near end flush with the support's far side, 1e-5 m deep at the support's edge
          const Quat q(Eigen::AngleAxisd(tilt, Vec3::UnitY()));
          const Vec3 edge(half, 0.0, 0.1 - 1e-5);
          const Vec3 centre = edge + q * Vec3(length - 2.0 * half, 0.0, 0.025);
          const RigidBody plank = Box(support_first ? 2 : 1, Vec3(length, 0.15, 0.025), centre, q);
          ContactSet out;
          const int n = support_first ? Collide(support, 0, plank, 1, 0.0, &out) : Collide(plank, 0, support, 1, 0.0, &out);
          const std::string where = "half " + std::to_string(half) + " length " + std::to_string(length) +
                                    " tilt " + std::to_string(tilt) + (support_first ? " support first" : " plank first");
          ASSERT_GE(n, 1) << where;
          for (const Contact& c : out) {
            EXPECT_LE(std::abs(c.point.x()), half + 1e-6) << where;
            EXPECT_LE(std::abs(c.point.y()), half + 1e-6) << where;
            EXPECT_LE(c.depth, 1e-5 + 2.0 * half * std::abs(tilt) + 1e-9) << where;
          }
          ++pairs;
        }
      }
    }
  }
  EXPECT_EQ(pairs, 48);
}

}  // namespace
}  // namespace contactsim
