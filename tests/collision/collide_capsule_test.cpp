// Hand-computed cases of the capsule pair functions, and capsule-box against
// brute-force candidate axes and dense sampling of the capsule's axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/collision/polyhedron_distance.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Capsule;
using testing_util::Convex;
using testing_util::Ground;
using testing_util::Hull;
using testing_util::MaxDepth;

// Closed forms on short decimals: round-off of a few ulps of 1 m. The
// capsule-polyhedron search compares distances, so near a smooth minimum it
// locates the point only to ~sqrt(machine epsilon) ~ 1.5e-8 of the axis
// length (the depth itself is exact to second order); points get 1e-6 m.
using testing_util::kTol;
constexpr double kSearchTol = 1e-6;   // m

const Quat kAlongX(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
const Quat kAlongY(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()));

bool HasContact(const ContactSet& out, const Vec3& point, const Vec3& normal, double depth, double tol) {
  return std::any_of(out.begin(), out.end(), [&](const Contact& c) {
    return (c.point - point).norm() < tol && (c.normal - normal).norm() < tol && std::abs(c.depth - depth) < tol;
  });
}

// Verifies crossed capsules: one contact between the axes' closest points.
TEST(CollideCapsuleTest, CrossedCapsulesTouchAtTheAxesClosestPoints) {
  ContactSet out;
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, Vec3::Zero(), kAlongX), 0, Capsule(2, 0.1, 0.5, Vec3(0, 0, 0.15), kAlongY),
                    1, 0.0, &out),
            1);
  EXPECT_TRUE(HasContact(out, Vec3(0, 0, 0.075), Vec3(0, 0, 1), 0.05, kTol));
}

// Verifies parallel capsules lying on each other: a contact at each end of the overlap.
TEST(CollideCapsuleTest, ParallelCapsulesTouchAtBothEndsOfTheOverlap) {
  ContactSet out;
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, Vec3::Zero(), kAlongX), 0, Capsule(2, 0.1, 0.5, Vec3(0.3, 0, 0.18), kAlongX),
                    1, 0.0, &out),
            2);
  EXPECT_TRUE(HasContact(out, Vec3(-0.2, 0, 0.09), Vec3(0, 0, 1), 0.02, kTol));
  EXPECT_TRUE(HasContact(out, Vec3(0.5, 0, 0.09), Vec3(0, 0, 1), 0.02, kTol));
}

// Verifies a capsule lying on the ground (two cap contacts) and standing on it (one).
TEST(CollideCapsuleTest, CapsuleOnPlaneLyingAndStanding) {
  ContactSet out;
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, Vec3(0, 0, 0.09), kAlongX), 0, Ground(2), 1, 0.0, &out), 2);
  EXPECT_TRUE(HasContact(out, Vec3(-0.5, 0, -0.005), Vec3(0, 0, -1), 0.01, kTol));
  EXPECT_TRUE(HasContact(out, Vec3(0.5, 0, -0.005), Vec3(0, 0, -1), 0.01, kTol));
  out.clear();
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, Vec3(0, 0, 0.59)), 0, Ground(2), 1, 0.0, &out), 1);
  EXPECT_TRUE(HasContact(out, Vec3(0, 0, -0.005), Vec3(0, 0, -1), 0.01, kTol));
}

// Verifies a capsule lying on a box's top face: two contacts, one under each cap.
TEST(CollideCapsuleTest, CapsuleLyingOnBoxGivesTwoContacts) {
  ContactSet out;
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, Vec3(0, 0, 0.59), kAlongX), 0, Box(2, Vec3(1, 1, 0.5), Vec3::Zero()), 1, 0.0,
                    &out),
            2);
  EXPECT_TRUE(HasContact(out, Vec3(-0.5, 0, 0.495), Vec3(0, 0, -1), 0.01, kTol));
  EXPECT_TRUE(HasContact(out, Vec3(0.5, 0, 0.495), Vec3(0, 0, -1), 0.01, kTol));
}

// Verifies a tilted capsule resting across a box's edge: one contact at the edge.
TEST(CollideCapsuleTest, CapsuleAcrossBoxEdgeTouchesTheEdge) {
  const double theta = 0.3;
  const Vec3 up(std::sin(theta), 0, std::cos(theta));  // axis normal, towards the capsule
  const Vec3 centre = Vec3(0.5, 0, 0.5) + 0.09 * up;
  const Quat q = Quat::FromTwoVectors(Vec3::UnitZ(), Vec3(std::cos(theta), 0, -std::sin(theta)));
  ContactSet out;
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.5, centre, q), 0, Box(2, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), 1, 0.0, &out), 1);
  EXPECT_TRUE(HasContact(out, centre - 0.095 * up, -up, 0.01, kSearchTol));
  EXPECT_NEAR(out[0].depth, 0.01, kTol);
}

// Verifies a capsule on a cube hull gives the same contacts as on the box.
TEST(CollideCapsuleTest, CapsuleOnCubeHullMatchesTheBox) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  const RigidBody capsule = Capsule(1, 0.1, 0.3, Vec3(0.1, 0.05, 0.58), kAlongX);
  ContactSet hull_out, box_out;
  Collide(capsule, 0, Convex(2, Hull(corners), Vec3::Zero()), 1, 0.0, &hull_out);
  Collide(capsule, 0, Box(2, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), 1, 0.0, &box_out);
  ASSERT_EQ(hull_out.size(), 2u);
  ASSERT_EQ(box_out.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_NEAR((hull_out[k].point - box_out[k].point).norm(), 0.0, kTol);
    EXPECT_NEAR(hull_out[k].depth, box_out[k].depth, kTol);
  }
}

// Largest separation of segment [p0, p1] (A) and a box (B) over the box's
// face normals and the crosses of the segment with the box's edges, both
// orientations, without pruning: minus the segment's penetration depth when
// they overlap (the faces of the polytope S - B are among these).
double SegmentBoxMaxSeparation(const Vec3& p0, const Vec3& p1, const RigidBody& box) {
  const Mat3 R = box.Rotation();
  std::vector<Vec3> axes;
  for (int k = 0; k < 3; ++k) {
    axes.push_back(R.col(k));
    const Vec3 c = (p1 - p0).cross(R.col(k));
    if (c.norm() > 1e-9) axes.push_back(c.normalized());
  }
  double best = -1e300;
  for (const Vec3& axis : axes) {
    for (const Vec3& u : {axis, Vec3(-axis)}) {
      double box_lo = u.dot(box.x);
      for (int k = 0; k < 3; ++k) box_lo -= box.shape.half_extents[k] * std::abs(u.dot(R.col(k)));
      best = std::max(best, box_lo - std::max(u.dot(p0), u.dot(p1)));
    }
  }
  return best;
}

// Verifies on random poses that the deepest capsule-box contact is
// r - sd(axis, box): r plus the axis's penetration depth (all candidate axes)
// when the axis pokes into the box, r minus its distance (dense samples of the
// axis) when apart; and that the contacts share one normal.
TEST(CollideCapsuleTest, CapsuleBoxDepthIsRadiusMinusAxisSignedDistance) {
  // 20001 samples of a 0.8 m axis are 4e-5 m apart; the distance is
  // 1-Lipschitz, so the sampled minimum is within half of that.
  constexpr int kSamples = 20001;
  constexpr double kSampleTol = 2e-5;  // m
  std::mt19937_64 rng(21);
  int overlapping = 0, apart = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const RigidBody capsule =
        Capsule(1, 0.15, 0.4, testing_util::RandomVector(rng, 0.5), testing_util::RandomRotation(rng));
    const RigidBody box = Box(2, Vec3(0.3, 0.2, 0.25), Vec3::Zero(), testing_util::RandomRotation(rng));
    ContactSet out;
    if (Collide(capsule, 0, box, 1, 0.2, &out) == 0) continue;
    for (const Contact& c : out) EXPECT_NEAR((c.normal - out[0].normal).norm(), 0.0, 1e-12);
    const Vec3 p0 = capsule.x - capsule.q * Vec3(0, 0, 0.4);
    const Vec3 p1 = capsule.x + capsule.q * Vec3(0, 0, 0.4);
    const double separation = SegmentBoxMaxSeparation(p0, p1, box);
    if (separation < 0.0) {
      EXPECT_NEAR(MaxDepth(out), 0.15 - separation, kTol);
      ++overlapping;
      continue;
    }
    double min_d = 1e300;
    for (int i = 0; i < kSamples; ++i) {
      min_d = std::min(min_d, BoxSignedDistance(box, p0 + (p1 - p0) * (double(i) / (kSamples - 1))).distance);
    }
    // the search is at least as deep as any sample, and no deeper than the
    // sampled minimum allows
    EXPECT_LE(MaxDepth(out), 0.15 - min_d + kSampleTol);
    EXPECT_GE(MaxDepth(out), 0.15 - min_d - kSearchTol);
    ++apart;
  }
  EXPECT_GT(overlapping, 20);
  EXPECT_GT(apart, 20);
}

// Verifies a capsule pushed halfway into a box's top face, lying flat: two
// contacts under the caps with the depth r + the axis's depth below the face
// (sampling the axis's point depths would give the same here, but the face,
// not the nearest face of each point, sets the normal).
TEST(CollideCapsuleTest, CapsuleSunkIntoBoxFacePushesOutOfThatFace) {
  ContactSet out;
  // axis 0.05 below the top face z = 0.5, along x, inside |x| <= 0.3 < 1
  ASSERT_EQ(Collide(Capsule(1, 0.1, 0.3, Vec3(0, 0, 0.45), kAlongX), 0, Box(2, Vec3(1, 1, 0.5), Vec3::Zero()), 1,
                    0.0, &out),
            2);
  for (const Contact& c : out) {
    EXPECT_NEAR(c.depth, 0.15, kTol);
    EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, kTol);
  }
}

// Verifies a capsule whose axis passes through a box near a vertical edge,
// tilted: the depth is set by the edge-axis cross product, deeper than any
// single point of the axis is inside the box.
TEST(CollideCapsuleTest, CapsuleThroughBoxCornerUsesTheEdgeAxis) {
  // an axis near the box's +x+y vertical edge, tilted in the diagonal plane:
  // it enters through the bottom and leaves through the top (PD 0.18 m along
  // the cross of the axis and the x edges; no point of it is 0.15 m deep)
  const RigidBody box = Box(2, Vec3(0.5, 0.5, 0.5), Vec3::Zero());
  const Quat q(Eigen::AngleAxisd(0.4, Vec3(1, -1, 0).normalized()));
  const RigidBody capsule = Capsule(1, 0.05, 0.8, Vec3(0.46, 0.46, 0), q);
  ContactSet out;
  ASSERT_GT(Collide(capsule, 0, box, 1, 0.0, &out), 0);
  const Vec3 p0 = capsule.x - capsule.q * Vec3(0, 0, 0.8);
  const Vec3 p1 = capsule.x + capsule.q * Vec3(0, 0, 0.8);
  const double separation = SegmentBoxMaxSeparation(p0, p1, box);
  ASSERT_LT(separation, 0.0);
  EXPECT_NEAR(MaxDepth(out), 0.05 - separation, kTol);
  // the deepest point of the axis is less deep than the segment's penetration
  double deepest_point = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    deepest_point = std::max(deepest_point, -BoxSignedDistance(box, p0 + (p1 - p0) * (i / 1000.0)).distance);
  }
  EXPECT_LT(deepest_point, -separation - 1e-3);
}

// Verifies a capsule lying exactly along an edge of a box's top face, its
// axis in the face's side plane up to round-off turns: both caps still give
// their contact over the face, at the segment's ends (a side plane the axis
// lies in must neither cut it at an arbitrary parameter nor drop it).
TEST(CollideCapsuleTest, CapsuleAlongATopEdgeKeepsBothEnds) {
  int cases = 0;
  for (const double half : {0.05, 0.2, 1.0}) {
    for (const double r : {0.01, 0.1}) {
      for (const double turn : {0.0, 3e-16, -1e-15, 4e-15}) {  // rad, about z
        const double len = 0.5 * half;                          // the capsule's half length, inside the face
        const Quat q = Quat(Eigen::AngleAxisd(turn, Vec3::UnitZ())) * kAlongX;
        const RigidBody capsule = Capsule(1, r, len, Vec3(0, half, half + r - 1e-6), q);
        ContactSet out;
        const std::string where = "half " + std::to_string(half) + " r " + std::to_string(r) + " turn " +
                                  std::to_string(turn);
        ASSERT_EQ(Collide(capsule, 0, Box(2, Vec3(half, half, half), Vec3::Zero()), 1, 0.0, &out), 2) << where;
        std::vector<double> xs;
        for (const Contact& c : out) {
          xs.push_back(c.point.x());
          EXPECT_NEAR(c.depth, 1e-6, 1e-9) << where;
          EXPECT_NEAR((c.normal - Vec3(0, 0, -1)).norm(), 0.0, 1e-9) << where;
        }
        std::sort(xs.begin(), xs.end());
        EXPECT_NEAR(xs[0], -len, 1e-9) << where;
        EXPECT_NEAR(xs[1], len, 1e-9) << where;
        ++cases;
      }
    }
  }
  EXPECT_EQ(cases, 24);
}

}  // namespace
}  // namespace contactsim
