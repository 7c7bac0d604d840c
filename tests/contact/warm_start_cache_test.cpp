// The warm-start cache (service/contact/warm_start_cache.h): impulses found
// by body pair and feature id, else by the pair's nearest cached point within
// kNearMatchDistance; kept bit for bit through Save and Restore.
#include "service/contact/warm_start_cache.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace contactsim {
namespace {

Contact MakeContact(BodyId a, BodyId b, uint32_t feature, const Vec3& point) {
  Contact c;
  c.id_a = a;
  c.id_b = b;
  c.feature_id = feature;
  c.point = point;
  return c;
}

// A cache holding one face's four corners of pair (1, 2), feature ids 10-13,
// impulses (k + 1, k, -k) for corner k.
WarmStartCache FourCorners(ContactSet* stored) {
  const double h = 0.1;
  const Vec3 corners[4] = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  std::vector<std::array<double, 3>> impulses;
  for (int k = 0; k < 4; ++k) {
    stored->push_back(MakeContact(1, 2, 10 + k, corners[k]));
    impulses.push_back({k + 1.0, 1.0 * k, -1.0 * k});
  }
  WarmStartCache cache;
  cache.StoreFrame(*stored, impulses);
  return cache;
}

TEST(WarmStartCacheTest, SameFeatureIdFindsItsImpulsesWhereverThePointMoved) {
  ContactSet stored;
  const WarmStartCache cache = FourCorners(&stored);
  // feature 12 moved 5 cm (a sliding contact): still its own impulses
  const std::array<double, 3>* found = cache.Find(MakeContact(1, 2, 12, stored[2].point + Vec3(0.05, 0, 0)));
  ASSERT_NE(found, nullptr);
  EXPECT_EQ((*found)[0], 3.0);
  EXPECT_EQ((*found)[1], 2.0);
  EXPECT_EQ((*found)[2], -2.0);
}

TEST(WarmStartCacheTest, NewFeatureIdTakesTheNearestCachedPointWithinTheDistance) {
  ContactSet stored;
  const WarmStartCache cache = FourCorners(&stored);
  const double d = WarmStartCache::kNearMatchDistance;
  // each corner under a new id, moved by 0.3 d in some direction
  const Vec3 moves[4] = {{0.3 * d, 0, 0}, {0, -0.3 * d, 0}, {0, 0, 0.3 * d}, {-0.2 * d, 0.2 * d, 0}};
  for (int k = 0; k < 4; ++k) {
    const std::array<double, 3>* found = cache.Find(MakeContact(1, 2, 99 + k, stored[k].point + moves[k]));
    ASSERT_NE(found, nullptr) << "corner " << k;
    EXPECT_EQ((*found)[0], k + 1.0) << "corner " << k;
  }
  // beyond the distance: nothing (a new contact starts from zero)
  EXPECT_EQ(cache.Find(MakeContact(1, 2, 99, stored[0].point + Vec3(1.01 * d, 0, 0))), nullptr);
  // the face's centre is far from every corner
  EXPECT_EQ(cache.Find(MakeContact(1, 2, 99, Vec3::Zero())), nullptr);
}

TEST(WarmStartCacheTest, PlaceMatchesOnlyWithinTheSamePair) {
  ContactSet stored;
  const WarmStartCache cache = FourCorners(&stored);
  EXPECT_EQ(cache.Find(MakeContact(1, 3, 10, stored[0].point)), nullptr);
  EXPECT_EQ(cache.Find(MakeContact(2, 1, 10, stored[0].point)), nullptr);
  EXPECT_EQ(cache.Find(MakeContact(0, 2, 50, stored[0].point)), nullptr);
}

TEST(WarmStartCacheTest, PointsWithoutNormalImpulseAreNotKept) {
  ContactSet contacts = {MakeContact(1, 2, 7, Vec3::Zero())};
  WarmStartCache cache;
  cache.StoreFrame(contacts, {{0.0, 1.0, 1.0}});
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(cache.Find(contacts[0]), nullptr);
}

TEST(WarmStartCacheTest, SaveAndRestoreKeepIdsImpulsesAndPlaces) {
  ContactSet stored;
  const WarmStartCache cache = FourCorners(&stored);
  WarmStartCache restored;
  ASSERT_TRUE(restored.Restore(cache.Save()));
  EXPECT_EQ(restored.Save(), cache.Save());
  // found by place after the round trip too
  const std::array<double, 3>* found = restored.Find(MakeContact(1, 2, 77, stored[3].point));
  ASSERT_NE(found, nullptr);
  EXPECT_EQ((*found)[0], 4.0);
  // truncated bytes are refused and change nothing
  const std::string bytes = cache.Save();
  EXPECT_FALSE(restored.Restore(bytes.substr(0, bytes.size() - 3)));
  EXPECT_EQ(restored.Save(), bytes);
}

}  // namespace
}  // namespace contactsim
