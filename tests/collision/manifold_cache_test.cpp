// Manifold reuse: kept manifolds at the current poses against a fresh
// Collide(), the motion bound that ends reuse, the rebuild's bookkeeping, and
// the same contacts for any number of threads.
#include "service/collision/manifold_cache.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/collision/parallel_runner.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace manifold_cache_test {  // a unity build shares the test files' anonymous namespaces
namespace {

using testing_util::Box;
using testing_util::Convex;
using testing_util::MaxDepth;
using testing_util::RockHull;

// soft's default margin (m)
constexpr double kMargin = 0.01;
// the largest motion of B's points in A's frame that keeps a manifold (m)
constexpr double kReach = kManifoldReuseFraction * kMargin;

void ExpectIdentical(const ContactSet& x, const ContactSet& y) {
  ASSERT_EQ(x.size(), y.size());
  for (size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(x[k].point, y[k].point);
    EXPECT_EQ(x[k].normal, y[k].normal);
    EXPECT_EQ(std::memcmp(&x[k].depth, &y[k].depth, sizeof(double)), 0);
    EXPECT_EQ(x[k].feature_id, y[k].feature_id);
    EXPECT_EQ(x[k].a, y[k].a);
    EXPECT_EQ(x[k].b, y[k].b);
    EXPECT_EQ(x[k].id_a, y[k].id_a);
    EXPECT_EQ(x[k].id_b, y[k].id_b);
  }
}

ContactSet Fresh(const std::vector<RigidBody>& bodies, const std::vector<BodyPair>& pairs) {
  ContactSet out;
  for (const BodyPair& p : pairs) Collide(bodies[p.first], p.first, bodies[p.second], p.second, kMargin, &out);
  return out;
}

ContactSet Detect(Narrowphase* np, const std::vector<RigidBody>& bodies, const std::vector<BodyPair>& pairs,
                  ParallelRunner& runner) {
  ContactSet out;
  np->CollidePairs(bodies, pairs, kMargin, runner, &out);
  return out;
}

// The farthest point of a box or hull from its origin (m).
double ReachOf(const RigidBody& body) {
  if (body.shape.type == ShapeType::kBox) return body.shape.half_extents.norm();
  double reach = 0.0;
  for (const Vec3& v : body.shape.hull->vertices) reach = std::max(reach, v.norm());
  return reach;
}

// Height of a box's or hull's highest (sign +1) or lowest (-1) point above its origin (m).
double Extent(const RigidBody& body, double sign) {
  if (body.shape.type == ShapeType::kBox) {
    const Mat3 R = body.Rotation();
    return (R.row(2).transpose().cwiseAbs()).dot(body.shape.half_extents);
  }
  double best = -1e300;
  for (const Vec3& v : body.shape.hull->vertices) best = std::max(best, sign * (body.q * v).z());
  return best;
}

// B placed on A's top with its lowest point 1 mm into A.
std::vector<RigidBody> OnTop(RigidBody a, RigidBody b) {
  b.x.z() = a.x.z() + Extent(a, 1.0) + Extent(b, -1.0) - 0.001;
  return {a, b};
}

// A 1 x 1 x 0.4 m slab as a hull, whose flat top a rock rests on.
std::shared_ptr<const ConvexHull> SlabHull() {
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k) corners.emplace_back(k & 1 ? 0.5 : -0.5, k & 2 ? 0.5 : -0.5, k & 4 ? 0.2 : -0.2);
  return testing_util::Hull(corners);
}

// The three polyhedron pairs, B resting on A's top face.
std::vector<std::vector<RigidBody>> RestingPairs() {
  const Quat tilt(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  return {
      OnTop(Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), Box(2, Vec3(0.3, 0.4, 0.2), Vec3(0.1, 0.05, 0.0), tilt)),
      OnTop(Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), Convex(2, RockHull(), Vec3(0.05, 0.0, 0.0))),
      OnTop(Convex(1, SlabHull(), Vec3::Zero()), Convex(2, RockHull(), Vec3(0.02, 0.01, 0.0), tilt)),
  };
}

// Verifies that a pair detected twice at the same poses gets its manifold
// back (one reuse) with the fresh points, normals and depths up to the
// round-off of the round trip through the bodies' frames, and the same
// feature ids (the warm start keys on them), for box-box, box-hull and
// hull-hull.
TEST(ManifoldCacheTest, AStillPairGetsItsManifoldBack) {
  ParallelRunner runner(1);
  int config = 0;
  for (const auto& bodies : RestingPairs()) {
    SCOPED_TRACE(config++);
    Narrowphase np;
    np.SetManifoldReuse(true);
    const std::vector<BodyPair> pairs = {{0, 1}};
    const ContactSet made = Detect(&np, bodies, pairs, runner);
    ASSERT_FALSE(made.empty());
    ExpectIdentical(made, Fresh(bodies, pairs));  // a miss is the fresh manifold, bit for bit
    EXPECT_EQ(np.manifolds().size(), 1u);
    const ContactSet kept = Detect(&np, bodies, pairs, runner);
    EXPECT_EQ(np.manifolds().reuses(), 1);
    ASSERT_EQ(kept.size(), made.size());
    for (size_t k = 0; k < kept.size(); ++k) {
      EXPECT_LT((kept[k].point - made[k].point).norm(), 1e-14);
      EXPECT_LT((kept[k].normal - made[k].normal).norm(), 1e-14);
      EXPECT_NEAR(kept[k].depth, made[k].depth, 1e-14);
      EXPECT_EQ(kept[k].feature_id, made[k].feature_id);
      EXPECT_EQ(kept[k].id_a, made[k].id_a);
      EXPECT_EQ(kept[k].b, made[k].b);
    }
  }
}

// Verifies, over random motions of B below the bound (shifts and turns of
// up to the reach), that the kept manifold's deepest point is within the
// reach of the fresh manifold's (reuse hides no overlap), and that a shift
// along the normal alone moves every kept depth by exactly the shift.
TEST(ManifoldCacheTest, KeptDepthsFollowTheBodiesWithinTheBound) {
  ParallelRunner runner(1);
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int kept_count = 0;
  for (const auto& start : RestingPairs()) {
    for (int trial = 0; trial < 50; ++trial) {
      Narrowphase np;
      np.SetManifoldReuse(true);
      const std::vector<BodyPair> pairs = {{0, 1}};
      const ContactSet made = Detect(&np, start, pairs, runner);
      std::vector<RigidBody> moved = start;
      // split the reach between the shift and the turn (the bound adds them)
      const double r_b = ReachOf(moved[1]);
      const Vec3 shift = 0.45 * kReach * Vec3(u(rng), u(rng), u(rng)).normalized();
      const double angle = 0.45 * kReach / r_b * std::abs(u(rng));
      moved[1].x += shift;
      moved[1].q = (Quat(Eigen::AngleAxisd(angle, Vec3(u(rng), u(rng), u(rng)).normalized())) * moved[1].q)
                       .normalized();
      const ContactSet kept = Detect(&np, moved, pairs, runner);
      ASSERT_EQ(np.manifolds().reuses(), 1) << "trial " << trial;
      ++kept_count;
      const ContactSet fresh = Fresh(moved, pairs);
      EXPECT_NEAR(MaxDepth(kept), MaxDepth(fresh), kReach) << "trial " << trial;
      EXPECT_GE(MaxDepth(kept), MaxDepth(fresh) - kReach);
    }
    // a shift along the (vertical) normal only
    Narrowphase np;
    np.SetManifoldReuse(true);
    const std::vector<BodyPair> pairs = {{0, 1}};
    const ContactSet made = Detect(&np, start, pairs, runner);
    std::vector<RigidBody> lowered = start;
    const double dz = 0.5 * kReach;
    lowered[1].x.z() -= dz;
    const ContactSet kept = Detect(&np, lowered, pairs, runner);
    ASSERT_EQ(kept.size(), made.size());
    for (size_t k = 0; k < kept.size(); ++k) {
      EXPECT_NEAR(kept[k].depth, made[k].depth + dz * made[k].normal.z(), 1e-12);
    }
  }
  EXPECT_EQ(kept_count, 150);
}

// Verifies that a motion beyond the bound (a shift, or a turn whose reach
// exceeds it) makes the manifold again: the fresh contacts bit for bit, and
// a remake counted; and that switching reuse off forgets the manifolds.
TEST(ManifoldCacheTest, MotionBeyondTheBoundMakesItAgain) {
  ParallelRunner runner(1);
  for (const auto& start : RestingPairs()) {
    for (int variant = 0; variant < 2; ++variant) {
      Narrowphase np;
      np.SetManifoldReuse(true);
      const std::vector<BodyPair> pairs = {{0, 1}};
      Detect(&np, start, pairs, runner);
      std::vector<RigidBody> moved = start;
      if (variant == 0) {
        moved[1].x.x() += 1.5 * kReach;
      } else {
        const double turn = 1.5 * kReach / ReachOf(moved[1]);
        moved[1].q = (Quat(Eigen::AngleAxisd(turn, Vec3::UnitX())) * moved[1].q).normalized();
      }
      const ContactSet again = Detect(&np, moved, pairs, runner);
      EXPECT_EQ(np.manifolds().reuses(), 0);
      EXPECT_EQ(np.manifolds().remakes(), 1);
      ExpectIdentical(again, Fresh(moved, pairs));
      np.SetManifoldReuse(false);
      EXPECT_EQ(np.manifolds().size(), 0u);
      ExpectIdentical(Detect(&np, moved, pairs, runner), Fresh(moved, pairs));
    }
  }
}

// Verifies that the rebuild keeps kept and stored manifolds, drops the
// pairs that made none, sorts, and counts.
TEST(ManifoldCacheTest, RebuildKeepsThisDetectionsManifolds) {
  ManifoldCache cache;
  std::vector<ManifoldUpdate> updates(3);
  updates[0].kind = ManifoldUpdate::Kind::kStore;
  updates[0].manifold.a = 7;
  updates[0].manifold.b = 9;
  updates[0].manifold.count = 1;
  updates[0].remakes = 1;
  updates[1].kind = ManifoldUpdate::Kind::kStore;
  updates[1].manifold.a = 2;
  updates[1].manifold.b = 3;
  // updates[2]: apart, nothing kept
  cache.Rebuild(updates);
  ASSERT_EQ(cache.size(), 2u);
  ASSERT_NE(cache.Find(2, 3), nullptr);
  ASSERT_NE(cache.Find(7, 9), nullptr);
  EXPECT_EQ(cache.Find(9, 7), nullptr);
  EXPECT_EQ(cache.remakes(), 1);
  // (7, 9) is kept, (2, 3) left the candidates
  std::vector<ManifoldUpdate> next(1);
  next[0].kind = ManifoldUpdate::Kind::kKeep;
  next[0].kept = static_cast<size_t>(cache.Find(7, 9) - cache.Find(2, 3));
  next[0].reuses = 1;
  cache.Rebuild(next);
  EXPECT_EQ(cache.size(), 1u);
  ASSERT_NE(cache.Find(7, 9), nullptr);
  EXPECT_EQ(cache.Find(7, 9)->count, 1);
  EXPECT_EQ(cache.reuses(), 1);
  cache.Clear();
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(cache.reuses(), 0);
}

// Verifies that a pile of touching boxes and hulls, nudged a little each
// detection (some pairs within the bound, some beyond), gets the same
// contacts and counters bit for bit on 1, 2 and 4 threads.
TEST(ManifoldCacheTest, ThreadCountsGiveTheSameContacts) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<RigidBody> bodies;
  BodyId id = 1;
  for (int i = 0; i < 12; ++i) {
    for (int level = 0; level < 3; ++level) {
      const Vec3 x(1.02 * i, 0.0, 1.0 * level);
      if ((i + level) % 3 == 0) {
        bodies.push_back(Convex(id++, RockHull(), x + Vec3(0.0, 0.0, 0.2)));
      } else {
        bodies.push_back(Box(id++, Vec3(0.5, 0.5, 0.5), x));
      }
    }
  }
  std::vector<BodyPair> pairs;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(bodies.size()); ++j) {
      if ((bodies[i].x - bodies[j].x).norm() < 1.6) pairs.push_back({i, j});
    }
  }
  ASSERT_GT(pairs.size(), 32u);  // above the parallel cut-off
  std::vector<std::vector<ContactSet>> runs;
  std::vector<int64_t> reuses;
  for (int threads : {1, 2, 4}) {
    ParallelRunner runner(threads);
    Narrowphase np;
    np.SetManifoldReuse(true);
    std::vector<RigidBody> world = bodies;
    std::mt19937_64 motion(11);
    std::uniform_real_distribution<double> m(-1.0, 1.0);
    runs.emplace_back();
    for (int step = 0; step < 20; ++step) {
      for (RigidBody& b : world) b.x += 0.7 * kReach * Vec3(m(motion), m(motion), m(motion));
      runs.back().push_back(Detect(&np, world, pairs, runner));
    }
    reuses.push_back(np.manifolds().reuses());
  }
  EXPECT_GT(reuses[0], 0);
  for (size_t t = 1; t < runs.size(); ++t) {
    EXPECT_EQ(reuses[t], reuses[0]);
    for (size_t s = 0; s < runs[t].size(); ++s) ExpectIdentical(runs[t][s], runs[0][s]);
  }
}

}  // namespace
}  // namespace manifold_cache_test
}  // namespace contactsim
