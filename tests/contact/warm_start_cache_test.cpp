// The warm-start cache (service/contact/warm_start_cache.h): impulses found
// by body pair and feature id, else by the pair's nearest cached point within
// kNearMatchDistance; kept bit for bit through Save and Restore.
#include "service/contact/warm_start_cache.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "tests/contact/keyed_contact.h"

namespace contactsim {
namespace {

using testing::KeyedContact;

// A cache holding one face's four corners of pair (1, 2), feature ids 10-13,
// impulses (k + 1, k, -k) for corner k.
WarmStartCache FourCorners(ContactSet* stored) {
  const double h = 0.1;
  const Vec3 corners[4] = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  std::vector<std::array<double, 3>> impulses;
  for (int k = 0; k < 4; ++k) {
    stored->push_back(KeyedContact(1, 2, 10 + k, corners[k]));
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
  const std::array<double, 3>* found = cache.Find(KeyedContact(1, 2, 12, stored[2].point + Vec3(0.05, 0, 0)));
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
    const std::array<double, 3>* found = cache.Find(KeyedContact(1, 2, 99 + k, stored[k].point + moves[k]));
    ASSERT_NE(found, nullptr) << "corner " << k;
    EXPECT_EQ((*found)[0], k + 1.0) << "corner " << k;
  }
  // beyond the distance: nothing (a new contact starts from zero)
  EXPECT_EQ(cache.Find(KeyedContact(1, 2, 99, stored[0].point + Vec3(1.01 * d, 0, 0))), nullptr);
  // the face's centre is far from every corner
  EXPECT_EQ(cache.Find(KeyedContact(1, 2, 99, Vec3::Zero())), nullptr);
}

TEST(WarmStartCacheTest, PlaceMatchesOnlyWithinTheSamePair) {
  ContactSet stored;
  const WarmStartCache cache = FourCorners(&stored);
  EXPECT_EQ(cache.Find(KeyedContact(1, 3, 10, stored[0].point)), nullptr);
  EXPECT_EQ(cache.Find(KeyedContact(2, 1, 10, stored[0].point)), nullptr);
  EXPECT_EQ(cache.Find(KeyedContact(0, 2, 50, stored[0].point)), nullptr);
}

TEST(WarmStartCacheTest, PointsWithoutNormalImpulseAreNotKept) {
  ContactSet contacts = {KeyedContact(1, 2, 7, Vec3::Zero())};
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
  const std::array<double, 3>* found = restored.Find(KeyedContact(1, 2, 77, stored[3].point));
  ASSERT_NE(found, nullptr);
  EXPECT_EQ((*found)[0], 4.0);
  // truncated bytes are refused and change nothing
  const std::string bytes = cache.Save();
  EXPECT_FALSE(restored.Restore(bytes.substr(0, bytes.size() - 3)));
  EXPECT_EQ(restored.Save(), bytes);
}

// 1 to 4 contacts for each of `pairs` body pairs, pair by pair in body
// order as the detector emits them, or shuffled; every 50th repeats the
// feature id before it (a hash collision: the first in contact order
// wins). A fifth have no normal impulse and are not kept.
ContactSet ManyContacts(int pairs, bool shuffled, std::vector<std::array<double, 3>>* impulses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  ContactSet contacts;
  for (int p = 0; p < pairs; ++p) {
    const int count = 1 + p % 4;
    for (int k = 0; k < count; ++k) {
      const uint32_t feature = contacts.size() % 50 == 49 && k > 0 ? 20 + k - 1 : 20 + k;
      contacts.push_back(KeyedContact(p, p + 1 + p % 3, feature, Vec3(value(rng), value(rng), value(rng))));
    }
  }
  if (shuffled) std::shuffle(contacts.begin(), contacts.end(), rng);
  impulses->clear();
  for (size_t k = 0; k < contacts.size(); ++k) {
    impulses->push_back({k % 5 == 4 ? 0.0 : 1.0 + value(rng), value(rng), value(rng)});
  }
  return contacts;
}

// Verifies that storing on 1, 2 and 4 threads gives the cache of a serial
// store bit for bit (the runs sorted apart and merged, or found in order
// and left), with 7,500 contacts in body order and shuffled, and that
// each kept contact finds its own impulses, the first of a repeated id
// winning.
TEST(WarmStartCacheTest, StoreOnThreadsGivesTheSerialCache) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const bool shuffled : {false, true}) {
    std::vector<std::array<double, 3>> impulses;
    const ContactSet contacts = ManyContacts(3000, shuffled, &impulses);
    WarmStartCache serial;
    serial.StoreFrame(contacts, impulses);
    std::map<std::tuple<BodyId, BodyId, uint32_t>, size_t> first;  // key -> first kept contact
    for (size_t k = 0; k < contacts.size(); ++k) {
      if (impulses[k][0] > 0.0) first.insert({{contacts[k].id_a, contacts[k].id_b, contacts[k].feature_id}, k});
    }
    ASSERT_EQ(serial.size(), static_cast<size_t>(std::count_if(impulses.begin(), impulses.end(),
                                                                [](const auto& l) { return l[0] > 0.0; })));
    for (const auto& [key, k] : first) {
      const std::array<double, 3>* found = serial.Find(contacts[k]);
      ASSERT_NE(found, nullptr) << "contact " << k;
      EXPECT_EQ(*found, impulses[k]) << "contact " << k << (shuffled ? " (shuffled)" : "");
    }
    for (const int threads : {1, 2, 4}) {
      ParallelRunner runner(threads);
      WarmStartCache cache;
      cache.StoreFrame(contacts, impulses, &runner);
      EXPECT_EQ(cache.Save(), serial.Save()) << threads << " threads" << (shuffled ? ", shuffled" : "");
    }
  }
}

// Verifies that Store, from constraint rows, keeps the same cache on 1, 2
// and 4 threads as without a runner.
TEST(WarmStartCacheTest, StoreFromRowsOnThreadsGivesTheSerialCache) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  std::vector<std::array<double, 3>> impulses;
  ContactSet contacts = ManyContacts(3000, true, &impulses);
  for (Contact& c : contacts) c.normal = Vec3(0.6, 0.0, 0.8);
  std::vector<ConstraintRow> rows(3 * contacts.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    for (int j = 0; j < 3; ++j) {
      rows[3 * k + j].lambda = impulses[k][j];
      rows[3 * k + j].lin_b = Vec3(j == 0, j == 1, j == 2);  // not the contact frame: turned into it
    }
  }
  WarmStartCache serial;
  serial.Store(contacts, rows);
  EXPECT_GT(serial.size(), 5000u);
  for (const int threads : {1, 2, 4}) {
    ParallelRunner runner(threads);
    WarmStartCache cache;
    cache.Store(contacts, rows, &runner);
    EXPECT_EQ(cache.Save(), serial.Save()) << threads << " threads";
  }
}

}  // namespace
}  // namespace contactsim
