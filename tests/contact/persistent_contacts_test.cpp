// Last step's contacts kept pair by pair (service/contact/persistent_contacts.h):
// every contact finds what WarmStartCache finds for it, by feature id or by
// place, however the contacts come (two ascending runs, as DetectAhead gives
// them, shuffled, a pair split apart, in chunks), and snapshots carry the
// same bytes as the cache's.
#include "service/contact/persistent_contacts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <optional>
#include <random>
#include <vector>

#include "service/contact/warm_start_cache.h"
#include "tests/contact/keyed_contact.h"

namespace contactsim {
namespace {

using testing::KeyedContact;

using Impulses = std::vector<std::array<double, 3>>;

// 1 to 4 contacts for each of `pairs` body pairs (A the lower id), pair by
// pair in body order, then every third pair moved after the others (the
// fast pairs DetectAhead collides again), or shuffled; every 50th repeats
// the feature id before it; a fifth have no normal impulse.
ContactSet LastStep(int pairs, bool shuffled, std::mt19937* rng, Impulses* impulses) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  ContactSet slow, fast;
  for (int p = 0; p < pairs; ++p) {
    ContactSet& into = p % 3 == 2 ? fast : slow;
    for (int k = 0; k < 1 + p % 4; ++k) {
      const size_t n = slow.size() + fast.size();
      const uint32_t feature = n % 50 == 49 && k > 0 ? 20 + k - 1 : 20 + k;
      into.push_back(KeyedContact(p, p + 1 + p % 3, feature, Vec3(value(*rng), value(*rng), value(*rng))));
    }
  }
  slow.insert(slow.end(), fast.begin(), fast.end());
  if (shuffled) std::shuffle(slow.begin(), slow.end(), *rng);
  impulses->clear();
  for (size_t k = 0; k < slow.size(); ++k) {
    impulses->push_back({k % 5 == 4 ? 0.0 : 1.0 + value(*rng), value(*rng), value(*rng)});
  }
  return slow;
}

// This step's contacts from last step's: each moved a little (within the
// near-match distance or beyond it), a third under a new feature id, a
// tenth of the pairs gone and as many new ones.
ContactSet ThisStep(const ContactSet& last, std::mt19937* rng) {
  const double d = WarmStartCache::kNearMatchDistance;
  std::uniform_real_distribution<double> move(-0.8 * d, 0.8 * d);
  std::uniform_int_distribution<int> pick(0, 29);
  ContactSet next;
  for (const Contact& c : last) {
    if (c.id_a % 10 == 3) continue;
    Contact m = c;
    const int draw = pick(*rng);
    if (draw < 10) m.feature_id += 100;
    m.point += draw % 4 == 0 ? Vec3(2.0 * d, 0, 0) : Vec3(move(*rng), move(*rng), move(*rng));
    next.push_back(m);
    if (c.id_a % 10 == 7) next.push_back(KeyedContact(c.id_a + 1000, c.id_b + 1000, c.feature_id, c.point));
  }
  return next;
}

std::vector<std::optional<std::array<double, 3>>> Matched(const PersistentContacts& kept, const ContactSet& contacts,
                                                          int chunk) {
  std::vector<std::optional<std::array<double, 3>>> found(contacts.size());
  const int n = static_cast<int>(contacts.size());
  for (int begin = 0; begin < n; begin += chunk) {
    kept.Match(contacts, begin, std::min(n, begin + chunk),
               [&](int k, const std::array<double, 3>& lambda) { found[k] = lambda; });
  }
  return found;
}

void ExpectTheCachesMatches(const WarmStartCache& cache, const PersistentContacts& kept, const ContactSet& contacts,
                            const char* what) {
  for (const int chunk : {static_cast<int>(contacts.size()), 7, 1}) {
    const auto found = Matched(kept, contacts, chunk);
    int hits = 0;
    for (size_t k = 0; k < contacts.size(); ++k) {
      const std::array<double, 3>* want = cache.Find(contacts[k]);
      ASSERT_EQ(found[k].has_value(), want != nullptr) << what << ", contact " << k << ", chunk " << chunk;
      if (want == nullptr) continue;
      EXPECT_EQ(*found[k], *want) << what << ", contact " << k << ", chunk " << chunk;
      ++hits;
    }
    EXPECT_GT(hits, static_cast<int>(contacts.size()) / 3) << what;
  }
}

TEST(PersistentContactsTest, EveryContactFindsWhatTheWarmStartCacheFinds) {
  std::mt19937 rng(11);
  for (const bool shuffled : {false, true}) {
    Impulses impulses;
    const ContactSet last = LastStep(2000, shuffled, &rng, &impulses);
    WarmStartCache cache;
    cache.StoreFrame(last, impulses);
    PersistentContacts kept;
    kept.Keep(last, [&](size_t k) { return impulses[k]; });
    EXPECT_EQ(kept.size(), cache.size());
    EXPECT_TRUE(kept.Save() == cache.Save()) << (shuffled ? "shuffled" : "two runs");
    ExpectTheCachesMatches(cache, kept, last, shuffled ? "the same contacts, shuffled" : "the same contacts");
    ContactSet next = ThisStep(last, &rng);
    ExpectTheCachesMatches(cache, kept, next, shuffled ? "moved, shuffled" : "moved, two runs");
    std::shuffle(next.begin(), next.end(), rng);
    ExpectTheCachesMatches(cache, kept, next, "moved and shuffled");
  }
}

// Verifies the choice between points as near: two kept points of a pair
// equally far from a new one (mirror images), the one with the smaller
// feature id wins whichever came first, and of two with one id, the first.
TEST(PersistentContactsTest, OfTwoPointsAsNearTheSmallerFeatureIdThenTheFirstWins) {
  const double d = 0.4 * WarmStartCache::kNearMatchDistance;
  for (const bool larger_first : {false, true}) {
    ContactSet last = {KeyedContact(1, 2, 30, Vec3(d, 0, 0)), KeyedContact(1, 2, 40, Vec3(-d, 0, 0)),
                       KeyedContact(1, 2, 40, Vec3(0, d, 0))};
    Impulses impulses = {{1.0, 0.0, 0.0}, {2.0, 0.0, 0.0}, {3.0, 0.0, 0.0}};
    if (larger_first) {
      std::swap(last[0], last[1]);
      std::swap(impulses[0], impulses[1]);
    }
    WarmStartCache cache;
    cache.StoreFrame(last, impulses);
    PersistentContacts kept;
    kept.Keep(last, [&](size_t k) { return impulses[k]; });
    const ContactSet next = {KeyedContact(1, 2, 99, Vec3::Zero()), KeyedContact(1, 2, 40, Vec3(5.0, 0, 0))};
    const auto found = Matched(kept, next, 2);
    ASSERT_TRUE(found[0].has_value());
    EXPECT_EQ((*found[0])[0], 1.0) << "feature 30 is the nearer's smaller id";
    ASSERT_TRUE(found[1].has_value());
    EXPECT_EQ((*found[1])[0], 2.0) << "of two points with id 40, the first";
    ExpectTheCachesMatches(cache, kept, next, larger_first ? "larger id first" : "smaller id first");
  }
}

// Verifies that a pair whose contacts come apart (not from the detectors)
// is kept as one, in contact order.
TEST(PersistentContactsTest, APairSplitApartIsKeptAsOne) {
  const ContactSet last = {KeyedContact(1, 2, 5, Vec3(0, 0, 0)), KeyedContact(3, 4, 5, Vec3(1, 0, 0)),
                           KeyedContact(1, 2, 5, Vec3(2, 0, 0)), KeyedContact(1, 2, 6, Vec3(3, 0, 0)),
                           KeyedContact(0, 9, 5, Vec3(4, 0, 0))};
  const Impulses impulses = {{1.0, 0, 0}, {2.0, 0, 0}, {3.0, 0, 0}, {4.0, 0, 0}, {5.0, 0, 0}};
  WarmStartCache cache;
  cache.StoreFrame(last, impulses);
  PersistentContacts kept;
  kept.Keep(last, [&](size_t k) { return impulses[k]; });
  EXPECT_TRUE(kept.Save() == cache.Save());
  ContactSet next = last;
  next.push_back(KeyedContact(1, 2, 77, Vec3(3, 0, 0)));
  ExpectTheCachesMatches(cache, kept, next, "split pair");
  const auto found = Matched(kept, next, 6);
  EXPECT_EQ((*found[2])[0], 1.0) << "the first of feature 5";
  EXPECT_EQ((*found[5])[0], 4.0) << "by place";
}

TEST(PersistentContactsTest, SaveAndRestoreKeepTheMatchesAndRefuseDamagedBytes) {
  std::mt19937 rng(5);
  Impulses impulses;
  const ContactSet last = LastStep(300, false, &rng, &impulses);
  PersistentContacts kept;
  kept.Keep(last, [&](size_t k) { return impulses[k]; });
  const std::string bytes = kept.Save();
  PersistentContacts restored;
  ASSERT_TRUE(restored.Restore(bytes));
  EXPECT_TRUE(restored.Save() == bytes);
  // the cache read back from the same bytes finds what the restored contacts find
  WarmStartCache cache;
  ASSERT_TRUE(cache.Restore(bytes));
  ExpectTheCachesMatches(cache, restored, ThisStep(last, &rng), "restored");
  EXPECT_FALSE(restored.Restore(bytes.substr(0, bytes.size() - 3)));
  EXPECT_TRUE(restored.Save() == bytes);
  ASSERT_TRUE(restored.Restore(""));
  EXPECT_EQ(restored.size(), 0u);
}

}  // namespace
}  // namespace contactsim
