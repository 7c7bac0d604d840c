// The separating-axis cache: bookkeeping, and through Narrowphase, hits on a
// coherent motion with results identical to the uncached Collide().
#include "service/collision/separating_axis_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "service/collision/posed_polyhedron.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Convex;
using testing_util::RockHull;

// Bit-for-bit equality: the cache may only skip work, never change results.
void ExpectIdentical(const ContactSet& x, const ContactSet& y) {
  ASSERT_EQ(x.size(), y.size());
  for (size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(x[k].point, y[k].point);
    EXPECT_EQ(x[k].normal, y[k].normal);
    EXPECT_EQ(std::memcmp(&x[k].depth, &y[k].depth, sizeof(double)), 0);
    EXPECT_EQ(x[k].feature_id, y[k].feature_id);
    EXPECT_EQ(x[k].a, y[k].a);
    EXPECT_EQ(x[k].id_b, y[k].id_b);
  }
}

// Verifies that a detection's rebuild keeps exactly the pairs it stored
// (hits hand their axis back as a store), drops erased, untouched and
// non-candidate pairs, sorts keys that came out of order, and counts.
TEST(SeparatingAxisCacheTest, RebuildKeepsOnlyThisDetectionsStores) {
  SeparatingAxisCache cache;
  const SeparatingAxis face{SeparatingAxis::Kind::kFaceA, 0, -1};
  const SeparatingAxis edges{SeparatingAxis::Kind::kEdges, 3, 4};
  cache.Store(1, 2, face);
  cache.Store(3, 4, face);  // not a candidate next time
  cache.Store(5, 6, face);  // touches next time
  std::vector<AxisCacheUpdate> updates(4);
  updates[0].Store(9, 10, edges);  // out of order: the rebuild sorts
  updates[0].misses = 1;
  updates[1].Store(1, 2, face);  // a hit
  updates[1].hits = 1;
  updates[2].Erase(5, 6);
  updates[2].misses = 1;
  // updates[3]: a pair that is no polyhedron pair changes nothing
  cache.Rebuild(updates);
  EXPECT_EQ(cache.size(), 2u);
  ASSERT_NE(cache.Find(1, 2), nullptr);
  EXPECT_TRUE(*cache.Find(1, 2) == face);
  ASSERT_NE(cache.Find(9, 10), nullptr);
  EXPECT_TRUE(*cache.Find(9, 10) == edges);
  EXPECT_EQ(cache.Find(3, 4), nullptr);
  EXPECT_EQ(cache.Find(5, 6), nullptr);
  EXPECT_EQ(cache.hits(), 1);
  EXPECT_EQ(cache.misses(), 2);
  // single stores still insert in order between rebuilt entries
  cache.Store(4, 1, edges);
  EXPECT_TRUE(*cache.Find(4, 1) == edges);
  EXPECT_TRUE(*cache.Find(1, 2) == face);
  EXPECT_TRUE(*cache.Find(9, 10) == edges);
}

// Verifies that axes are stored per ordered pair, erased, and cleared with the counters.
TEST(SeparatingAxisCacheTest, StoresFindsErasesAndClears) {
  SeparatingAxisCache cache;
  EXPECT_EQ(cache.Find(1, 2), nullptr);
  cache.Store(1, 2, {SeparatingAxis::Kind::kEdges, 3, 4});
  ASSERT_NE(cache.Find(1, 2), nullptr);
  EXPECT_TRUE((*cache.Find(1, 2) == SeparatingAxis{SeparatingAxis::Kind::kEdges, 3, 4}));
  EXPECT_EQ(cache.Find(2, 1), nullptr);
  // boxes 1 and 2 apart along x: face 0 of A (+x) separates, nothing stored for (2, 1)
  const RigidBody a = Box(1, Vec3(0.5, 0.5, 0.5), Vec3::Zero());
  const RigidBody b = Box(2, Vec3(0.5, 0.5, 0.5), Vec3(2, 0, 0));
  cache.Store(1, 2, {SeparatingAxis::Kind::kFaceA, 0, -1});
  EXPECT_TRUE(cache.StillSeparates(a, b, 0.0));
  EXPECT_FALSE(cache.StillSeparates(b, a, 0.0));
  EXPECT_EQ(cache.hits(), 1);
  EXPECT_EQ(cache.misses(), 1);
  cache.Erase(1, 2);
  EXPECT_EQ(cache.Find(1, 2), nullptr);
  cache.Store(5, 6, {SeparatingAxis::Kind::kFaceA, 0, -1});
  cache.Clear();
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(cache.hits(), 0);
  EXPECT_EQ(cache.misses(), 0);
}

// Verifies on a coherent sequence (a box and a hull tumbling past a box, in and
// out of contact) that the cache hits and gives exactly the uncached results.
TEST(SeparatingAxisCacheTest, CoherentMotionHitsAndMatchesUncached) {
  constexpr int kSteps = 600;
  constexpr double kMargin = 0.01;  // m
  Narrowphase cached;
  const RigidBody base = Box(1, Vec3(0.5, 0.4, 0.3), Vec3::Zero());
  int steps_with_contacts = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double t = k / 100.0;  // s, 100 Hz
    // a slow orbit at ~0.85 m radius with a wobble that brings it into contact
    const Vec3 x(0.85 * std::cos(t), 0.85 * std::sin(t), 0.2 * std::sin(3 * t));
    const Quat q(Eigen::AngleAxisd(0.7 * t, Vec3(1, 2, 3).normalized()));
    for (const RigidBody& mover : {Box(2, Vec3(0.3, 0.2, 0.25), x, q), Convex(3, RockHull(), x, q)}) {
      ContactSet with_cache, without;
      cached.Collide(base, 0, mover, 1, kMargin, &with_cache);
      Collide(base, 0, mover, 1, kMargin, &without);
      ExpectIdentical(with_cache, without);
      // the swapped call shares the same cache entry (canonical order)
      ContactSet swapped_cached, swapped;
      cached.Collide(mover, 1, base, 0, kMargin, &swapped_cached);
      Collide(mover, 1, base, 0, kMargin, &swapped);
      ExpectIdentical(swapped_cached, swapped);
      steps_with_contacts += !without.empty();
    }
  }
  const SeparatingAxisCache& cache = cached.cache();
  EXPECT_GT(steps_with_contacts, 0);
  EXPECT_GT(cache.hits(), 0);
  EXPECT_EQ(cache.hits() + cache.misses(), 4 * kSteps);
  // every call in contact must run the full test; of the separated calls
  // (two per mover and step) nearly all should be settled by the cached axis
  const int separated_calls = 4 * kSteps - 2 * steps_with_contacts;
  const double hit_rate = static_cast<double>(cache.hits()) / separated_calls;
  EXPECT_GT(hit_rate, 0.9) << "hits " << cache.hits() << " misses " << cache.misses()
                           << " separated calls " << separated_calls;
  cached.Reset();
  EXPECT_EQ(cached.cache().hits(), 0);
  EXPECT_EQ(cached.cache().size(), 0u);
}

// Verifies on random poses that a cached axis, tested on the bodies' own
// frames, separates exactly when the posed polyhedra's separation along it
// exceeds the margin: faces of A, faces of B and edge pairs of boxes and hulls.
TEST(SeparatingAxisCacheTest, BodyFrameTestAgreesWithPosedSeparation) {
  // separations of ~1 m bodies computed two ways differ by round-off ~1e-15 m
  constexpr double kRoundOff = 1e-12;  // m
  std::mt19937_64 rng(17);
  int compared = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const RigidBody a = trial % 2 == 0 ? Box(1, Vec3(0.4, 0.25, 0.15), Vec3::Zero(), testing_util::RandomRotation(rng))
                                       : Convex(1, RockHull(), Vec3::Zero(), testing_util::RandomRotation(rng));
    const RigidBody b = Convex(2, RockHull(), testing_util::RandomVector(rng, 0.8), testing_util::RandomRotation(rng));
    PosedPolyhedron pa, pb;
    ASSERT_TRUE(PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb));
    std::vector<SeparatingAxis> axes;
    for (int f = 0; f < static_cast<int>(pa.normals.size()); ++f) axes.push_back({SeparatingAxis::Kind::kFaceA, f, -1});
    for (int f = 0; f < static_cast<int>(pb.normals.size()); ++f) axes.push_back({SeparatingAxis::Kind::kFaceB, -1, f});
    for (int e = 0; e < 5; ++e) axes.push_back({SeparatingAxis::Kind::kEdges, e, 2 * e + 1});
    for (const SeparatingAxis& axis : axes) {
      Vec3 n;
      double sep;
      if (!AxisSeparation(pa, pb, axis, &n, &sep)) continue;
      SeparatingAxisCache cache;
      cache.Store(1, 2, axis);
      EXPECT_TRUE(cache.StillSeparates(a, b, sep - kRoundOff)) << "trial " << trial;
      EXPECT_FALSE(cache.StillSeparates(a, b, sep + kRoundOff)) << "trial " << trial;
      ++compared;
    }
  }
  EXPECT_GT(compared, 2000);
}

// Verifies that bodies without distinct ids (no world) bypass the cache.
TEST(SeparatingAxisCacheTest, EqualIdsBypassTheCache) {
  Narrowphase cached;
  ContactSet out;
  cached.Collide(Box(0, Vec3(0.5, 0.5, 0.5), Vec3::Zero()), 0, Box(0, Vec3(0.5, 0.5, 0.5), Vec3(3, 0, 0)), 1, 0.0,
                 &out);
  EXPECT_EQ(cached.cache().hits() + cached.cache().misses(), 0);
  EXPECT_EQ(cached.cache().size(), 0u);
}

}  // namespace
}  // namespace contactsim
