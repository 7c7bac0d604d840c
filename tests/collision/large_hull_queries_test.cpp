// The shortcuts that make hulls of hundreds of vertices cheap give exactly
// what the scans they replace give: the Gauss-map grid's edge pairs are the
// double loop's Minkowski-face pairs, the descent's support value is the
// scan's, a small pair's Gauss-map tables accept the loop's pairs, and a
// hull's box found by descent is the scanned box, bit for bit,
// on random hulls (ellipsoid-like clouds, elongated ones, few and many
// points) in random poses, whatever vertex the descents start from.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/minkowski_edge_pairs.h"
#include "service/collision/polyhedron_sat.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Convex;
using testing_util::Hull;
using testing_util::RandomRotation;
using testing_util::RandomVector;

constexpr int kHullTrials = 20;

// `count` points on an ellipsoid of semi-axes `axes` (m), jittered inwards,
// as a tessellated link or wheel gives.
std::vector<Vec3> Cloud(std::mt19937_64& rng, int count, const Vec3& axes) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> shrink(0.97, 1.0);
  std::vector<Vec3> points;
  for (int i = 0; i < count; ++i) {
    const Vec3 u = Vec3{normal(rng), normal(rng), normal(rng)}.normalized();
    points.push_back(shrink(rng) * u.cwiseProduct(axes));
  }
  return points;
}

RigidBody RandomHullBody(std::mt19937_64& rng, BodyId id, int count) {
  std::uniform_real_distribution<double> axis(0.02, 0.4);
  const Vec3 axes{axis(rng), axis(rng), axis(rng)};
  return Convex(id, Hull(Cloud(rng, count, axes)), RandomVector(rng, 0.3), RandomRotation(rng));
}

// The pairs of the double loop that IsMinkowskiFace accepts, as ea * E_b + eb.
std::vector<int64_t> LoopPairs(const PosedPolyhedron& a, const PosedPolyhedron& b) {
  std::vector<int64_t> pairs;
  const int edges_b = static_cast<int>(b.edge_dirs.size());
  for (int ea = 0; ea < static_cast<int>(a.edge_dirs.size()); ++ea) {
    const auto& fa = a.topology->edge_faces[ea];
    for (int eb = 0; eb < edges_b; ++eb) {
      const auto& fb = b.topology->edge_faces[eb];
      if (IsMinkowskiFace(a.normals[fa[0]], a.normals[fa[1]], -b.normals[fb[0]], -b.normals[fb[1]])) {
        pairs.push_back(static_cast<int64_t>(ea) * edges_b + eb);
      }
    }
  }
  return pairs;
}

TEST(LargeHullQueries, GridFindsExactlyTheMinkowskiFacePairsInLoopOrder) {
  std::mt19937_64 rng(7);
  EdgePairScratch scratch;
  for (int trial = 0; trial < kHullTrials; ++trial) {
    for (const int count : {8, 60, 400}) {
      // the bodies own the hulls the posed polyhedra point at
      const RigidBody body_a = RandomHullBody(rng, 1, count), body_b = RandomHullBody(rng, 2, 500 - count);
      PosedPolyhedron a, b;
      ASSERT_TRUE(PosePolyhedron(body_a, &a));
      ASSERT_TRUE(PosePolyhedron(body_b, &b));
      ASSERT_TRUE(HasClosedTopology(a) && HasClosedTopology(b));
      MinkowskiEdgePairs(a, b, &scratch);
      const std::vector<int64_t> expected = LoopPairs(a, b);
      EXPECT_EQ(scratch.pairs, expected) << "trial " << trial << ", " << count << " points";
      // a Minkowski difference has about as many edge faces as both have edges
      EXPECT_LE(scratch.pairs.size(), 4 * (a.edge_dirs.size() + b.edge_dirs.size()));
    }
  }
}

TEST(LargeHullQueries, BoxesPairWithHullsAsTheLoopPairsThem) {
  std::mt19937_64 rng(11);
  EdgePairScratch scratch;
  for (int trial = 0; trial < kHullTrials; ++trial) {
    const RigidBody hull = RandomHullBody(rng, 2, 300);
    PosedPolyhedron a, b;
    ASSERT_TRUE(PosePolyhedron(testing_util::Box(1, Vec3(0.3, 0.1, 0.05), Vec3::Zero(), RandomRotation(rng)), &a));
    ASSERT_TRUE(PosePolyhedron(hull, &b));
    MinkowskiEdgePairs(a, b, &scratch);
    EXPECT_EQ(scratch.pairs, LoopPairs(a, b));
    MinkowskiEdgePairs(b, a, &scratch);
    EXPECT_EQ(scratch.pairs, LoopPairs(b, a));
  }
}

// Verifies that the Gauss-map tables of small pairs (boxes, and hulls of 8
// and 12 points, each way round) accept exactly the double loop's pairs,
// and that a table too large for its bound is refused.
TEST(LargeHullQueries, GaussArcTableAcceptsExactlyTheLoopPairs) {
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < kHullTrials; ++trial) {
    const RigidBody box = testing_util::Box(1, Vec3(0.3, 0.1, 0.05), RandomVector(rng, 0.3), RandomRotation(rng));
    const RigidBody small = RandomHullBody(rng, 2, 8), medium = RandomHullBody(rng, 3, 12);
    for (const RigidBody* first : {&box, &small, &medium}) {
      for (const RigidBody* other : {&box, &small, &medium}) {
        PosedPolyhedron a, b;
        ASSERT_TRUE(PosePolyhedron(*first, &a));
        ASSERT_TRUE(PosePolyhedron(*other, &b));
        GaussArcTable table;
        ASSERT_TRUE(table.Build(a, b));
        std::vector<int64_t> pairs;
        const int edges_b = static_cast<int>(b.edge_dirs.size());
        for (int ea = 0; ea < static_cast<int>(a.edge_dirs.size()); ++ea) {
          for (int eb = 0; eb < edges_b; ++eb) {
            if (table.IsMinkowskiFace(ea, eb)) pairs.push_back(static_cast<int64_t>(ea) * edges_b + eb);
          }
        }
        EXPECT_EQ(pairs, LoopPairs(a, b)) << "trial " << trial;
      }
    }
  }
  // 400 points: hundreds of edges against hundreds of faces
  const RigidBody large_a = RandomHullBody(rng, 1, 400), large_b = RandomHullBody(rng, 2, 400);
  PosedPolyhedron a, b;
  ASSERT_TRUE(PosePolyhedron(large_a, &a));
  ASSERT_TRUE(PosePolyhedron(large_b, &b));
  GaussArcTable table;
  EXPECT_FALSE(table.Build(a, b));
}

TEST(LargeHullQueries, DescentFindsTheScannedMinimumFromAnyStart) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < kHullTrials; ++trial) {
    const RigidBody body = RandomHullBody(rng, 1, 300);
    PosedPolyhedron poly;
    ASSERT_TRUE(PosePolyhedron(body, &poly));
    ASSERT_GE(static_cast<int>(poly.vertices.size()), kDescentMinVertices);
    for (int k = 0; k < 20; ++k) {
      const Vec3 n = RandomVector(rng, 1.0).normalized();
      double scan = 1e300;
      for (const Vec3& v : poly.vertices) scan = std::min(scan, n.dot(v));
      int start = static_cast<int>(rng() % poly.vertices.size());
      EXPECT_EQ(MinProjection(poly, n, &start), scan);
      EXPECT_EQ(n.dot(poly.vertices[start]), scan);
    }
  }
}

TEST(LargeHullQueries, BoxByDescentIsTheScannedBox) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < kHullTrials; ++trial) {
    const RigidBody body = RandomHullBody(rng, 1, 300);
    AabbSupport support;
    for (int& v : support) v = static_cast<int>(rng() % body.shape.hull->vertices.size());
    for (int turn = 0; turn < 5; ++turn) {
      RigidBody moved = body;
      moved.q = RandomRotation(rng);
      const Aabb scanned = ComputeAabb(moved, 0.01, 0.0);
      const Aabb descended = ComputeAabb(moved, 0.01, 0.0, &support);
      EXPECT_EQ(descended.min, scanned.min);
      EXPECT_EQ(descended.max, scanned.max);
    }
  }
}

// The separating-axis test on large hulls (grid and descents) against the
// brute-force maximum over every face normal and edge pair.
TEST(LargeHullQueries, SeparatingAxisOfLargeHullsMatchesBruteForce) {
  std::mt19937_64 rng(13);
  EdgePairScratch scratch;
  int overlaps = 0;
  for (int trial = 0; trial < kHullTrials; ++trial) {
    const RigidBody body_a = RandomHullBody(rng, 1, 200), body_b = RandomHullBody(rng, 2, 200);
    PosedPolyhedron a, b;
    ASSERT_TRUE(PosePolyhedron(body_a, &a));
    ASSERT_TRUE(PosePolyhedron(body_b, &b));
    const SatResult sat = FindSeparatingAxis(a, b, 1e300, &scratch);
    double brute = -1e300;
    const auto separation = [&](const Vec3& u) {
      double lo_a, hi_a, lo_b, hi_b;
      ProjectPolyhedron(a, u, &lo_a, &hi_a);
      ProjectPolyhedron(b, u, &lo_b, &hi_b);
      return std::max(lo_b - hi_a, lo_a - hi_b);
    };
    for (const auto* p : {&a, &b}) {
      for (const Vec3& n : p->normals) brute = std::max(brute, separation(n));
    }
    for (const Vec3& da : a.edge_dirs) {
      for (const Vec3& db : b.edge_dirs) {
        const Vec3 c = da.cross(db);
        if (c.norm() > 1e-9) brute = std::max(brute, separation(c.normalized()));
      }
    }
    // overlapping, the Minkowski faces hold the least-penetrating axis, so
    // the maximum over them is the maximum over all (to round-off); apart,
    // it is only a lower bound
    if (brute < 0.0) {
      ++overlaps;
      EXPECT_NEAR(sat.max_separation, brute, 1e-12) << "trial " << trial;
    } else {
      EXPECT_LE(sat.max_separation, brute + 1e-12) << "trial " << trial;
    }
  }
  EXPECT_GE(overlaps, kHullTrials / 4);
}

}  // namespace
}  // namespace contactsim
