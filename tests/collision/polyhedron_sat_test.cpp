// The separating-axis test against brute-force references on random poses
// (as MuJoCo's box-box fuzz tests): every candidate axis without pruning, and
// a dense sampling of directions for the true penetration depth.
#include "service/collision/polyhedron_sat.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::RandomVector;

// Projections of a few vertices of size ~1 m: round-off is ~1e-15 m.
using testing_util::kTol;
// Fibonacci-sphere directions; the sampled minimum overlap can only be above
// the true depth, so no tolerance on that side is needed beyond round-off.
constexpr int kDirections = 4000;
constexpr int kSatTrials = 400;

double Separation(const PosedPolyhedron& a, const PosedPolyhedron& b, const Vec3& u) {
  double lo_a, hi_a, lo_b, hi_b;
  ProjectPolyhedron(a, u, &lo_a, &hi_a);
  ProjectPolyhedron(b, u, &lo_b, &hi_b);
  return std::max(lo_b - hi_a, lo_a - hi_b);
}

// Largest separation over every face normal and every edge pair (all edges,
// no de-duplication), both orientations.
double BruteForceMaxSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b) {
  double best = -1e300;
  for (const auto* p : {&a, &b}) {
    for (const Vec3& n : p->normals) best = std::max(best, Separation(a, b, n));
  }
  for (const auto& ea : a.topology->edges) {
    const Vec3 da = a.vertices[ea[1]] - a.vertices[ea[0]];
    for (const auto& eb : b.topology->edges) {
      const Vec3 c = da.cross(b.vertices[eb[1]] - b.vertices[eb[0]]);
      if (c.norm() < 1e-9) continue;
      best = std::max(best, Separation(a, b, c.normalized()));
    }
  }
  return best;
}

// Largest separation over sampled directions (minus the smallest overlap).
double SampledMaxSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b) {
  double best = -1e300;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kDirections;
    const double r = std::sqrt(1.0 - z * z);
    const Vec3 u(r * std::cos(golden * i), r * std::sin(golden * i), z);
    best = std::max(best, Separation(a, b, u));
  }
  return best;
}

// Deepest a preferred axis may be when the true depth is `depth` (m): the
// relative preference (faces of B, then edges) compounded, capped at
// kSatMaxBias, plus the absolute tolerance of each (polyhedron_sat.h).
double PreferredDepthBound(double depth) {
  const double relative = depth / (kSatEdgeRelTolerance * kSatFaceRelTolerance);
  return std::min(relative, depth + kSatMaxBias) + 2 * kSatAbsTolerance + kTol;
}

struct Pair {
  PosedPolyhedron a, b;
  RigidBody body_a, body_b;
};

Pair RandomPair(int kind, std::mt19937_64& rng) {
  static const auto rock = testing_util::RockHull();
  const Shape box_a = Shape::Box(Vec3(0.4, 0.25, 0.15));
  const Shape box_b = Shape::Box(Vec3(0.3, 0.3, 0.2));
  const Shape hull = Shape::Convex(rock);
  Pair p;
  p.body_a = MakeBody(1, kind == 2 ? hull : box_a, Vec3::Zero(), RandomRotation(rng));
  p.body_b = MakeBody(2, kind == 0 ? box_b : hull, RandomVector(rng, 0.55), RandomRotation(rng));
  PosePolyhedron(p.body_a, &p.a);
  PosePolyhedron(p.body_b, &p.b);
  return p;
}

// Verifies against the brute-force maximum over all candidate axes: equal when
// the bodies overlap (the pruned edge pairs can only overlap more), never above
// it and of the same sign when they are apart, and the chosen axis within the
// preference tolerances.
TEST(PolyhedronSatTest, MatchesBruteForceOverAllCandidateAxes) {
  std::mt19937_64 rng(3);
  for (int kind = 0; kind < 3; ++kind) {  // box-box, box-convex, convex-convex
    int overlapping = 0;
    for (int trial = 0; trial < kSatTrials; ++trial) {
      const Pair p = RandomPair(kind, rng);
      const double brute = BruteForceMaxSeparation(p.a, p.b);
      const SatResult sat = FindSeparatingAxis(p.a, p.b, 1e300);
      if (brute <= 0.0) {
        EXPECT_NEAR(sat.max_separation, brute, kTol) << "kind " << kind << " trial " << trial;
      } else {
        EXPECT_LE(sat.max_separation, brute + kTol) << "kind " << kind << " trial " << trial;
        EXPECT_GT(sat.max_separation, 0.0) << "kind " << kind << " trial " << trial;
      }
      EXPECT_LE(sat.separation, sat.max_separation);
      Vec3 n;
      double sep;
      ASSERT_TRUE(AxisSeparation(p.a, p.b, sat.axis, &n, &sep));
      EXPECT_NEAR(sep, sat.separation, kTol);
      EXPECT_NEAR(n.norm(), 1.0, kTol);
      if (brute < 0.0) {
        ++overlapping;
        // depth of the chosen axis within the preference band of the true depth
        EXPECT_LE(-sat.separation, PreferredDepthBound(-brute));
        // the unbiased axis overlaps by exactly the true depth
        EXPECT_NEAR(sat.max_normal.norm(), 1.0, kTol);
        EXPECT_NEAR(Separation(p.a, p.b, sat.max_normal), sat.max_separation, kTol);
      }
    }
    EXPECT_GT(overlapping, kSatTrials / 5) << "kind " << kind;
  }
}

// Verifies that the candidate axes are complete: no sampled direction overlaps
// less than the SAT depth, i.e. the SAT depth is the true penetration depth.
TEST(PolyhedronSatTest, DepthIsTheMinimumOverlapOverAllDirections) {
  std::mt19937_64 rng(5);
  for (int kind = 0; kind < 3; ++kind) {
    for (int trial = 0; trial < kSatTrials / 4; ++trial) {
      const Pair p = RandomPair(kind, rng);
      const SatResult sat = FindSeparatingAxis(p.a, p.b, 1e300);
      if (sat.max_separation >= 0.0) continue;
      EXPECT_GE(sat.max_separation, SampledMaxSeparation(p.a, p.b) - kTol) << "kind " << kind;
    }
  }
}

// Verifies the manifold against the references: contacts exist iff the bodies
// overlap, share one unit normal, are at most four, and the deepest has the
// chosen axis's depth (itself within the preference band of the true depth),
// except where the vertex that sets that depth lies outside the reference
// body (a preferred face's far vertex beside it): there the deepest point
// is shallower, but no shallower than the true depth less the band.
TEST(PolyhedronSatTest, ManifoldIsNoDeeperThanTheTruePenetration) {
  std::mt19937_64 rng(9);
  int colliding = 0, shallower = 0;
  for (int kind = 0; kind < 3; ++kind) {
    for (int trial = 0; trial < kSatTrials; ++trial) {
      const Pair p = RandomPair(kind, rng);
      const double brute = BruteForceMaxSeparation(p.a, p.b);
      if (std::abs(brute) < 1e-9) continue;  // grazing: either answer is right
      ContactSet out;
      Collide(p.body_a, 0, p.body_b, 1, 0.0, &out);
      EXPECT_EQ(!out.empty(), brute < 0.0) << "kind " << kind << " trial " << trial;
      EXPECT_LE(out.size(), 4u);
      if (!out.empty()) {
        const SatResult sat = FindSeparatingAxis(p.a, p.b, 1e300);
        const double deepest = testing_util::MaxDepth(out);
        EXPECT_LE(deepest, -sat.separation + 1e-9) << "kind " << kind << " trial " << trial;
        EXPECT_GE(deepest, -brute - kSatMaxBias - kTol) << "kind " << kind << " trial " << trial;
        ++colliding;
        if (deepest < -sat.separation - 1e-9) ++shallower;
      }
      const double bound = PreferredDepthBound(-brute);
      for (const Contact& c : out) {
        EXPECT_LE(c.depth, bound);
        EXPECT_NEAR((c.normal - out[0].normal).norm(), 0.0, kTol);
        EXPECT_NEAR(c.normal.norm(), 1.0, kTol);
      }
    }
  }
  std::printf("%d colliding pairs, %d with the deepest point shallower than the axis\n", colliding, shallower);
  EXPECT_LT(shallower, colliding / 20);
}

}  // namespace
}  // namespace contactsim
