// The separating-axis cache: bookkeeping, and through Narrowphase, hits on a
// coherent motion with results identical to the uncached Collide().
#include "service/collision/separating_axis_cache.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "service/collision/narrowphase.h"
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

// Verifies that axes are stored per ordered pair, erased, and cleared with the counters.
TEST(SeparatingAxisCacheTest, StoresFindsErasesAndClears) {
  SeparatingAxisCache cache;
  EXPECT_EQ(cache.Find(1, 2), nullptr);
  cache.Store(1, 2, {SeparatingAxis::Kind::kEdges, 3, 4});
  ASSERT_NE(cache.Find(1, 2), nullptr);
  EXPECT_TRUE((*cache.Find(1, 2) == SeparatingAxis{SeparatingAxis::Kind::kEdges, 3, 4}));
  EXPECT_EQ(cache.Find(2, 1), nullptr);
  cache.CountHit();
  cache.CountMiss();
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
