#include "service/contact/persistent_contacts.h"

#include <algorithm>
#include <iterator>
#include <tuple>

#include "service/contact/saved_impulses.h"
#include "service/contact/warm_start_cache.h"

namespace contactsim {

const PersistentContacts::Pair* PersistentContacts::FindPair(const Contact& c, Walk* walk) const {
  const Pair key{c.id_a, c.id_b, 0, 0};
  if (walk->started && !(key < walk->last)) {
    // on from the last pair's place: each kept pair is passed once a run
    while (walk->at < pairs_.size() && pairs_[walk->at] < key) ++walk->at;
  } else {
    walk->at = static_cast<size_t>(std::lower_bound(pairs_.begin(), pairs_.end(), key) - pairs_.begin());
  }
  walk->started = true;
  walk->last = key;
  const bool found = walk->at < pairs_.size() && !(key < pairs_[walk->at]);
  return found ? &pairs_[walk->at] : nullptr;
}

const std::array<double, 3>* PersistentContacts::Nearest(const Pair& pair, const Contact& c) const {
  // WarmStartCache::Near's choice, whose entries are in feature order
  const Point* begin = points_.data() + pair.first;
  const Point* end = begin + pair.count;
  const Point* best = nullptr;
  double best_d2 = WarmStartCache::kNearMatchDistance * WarmStartCache::kNearMatchDistance;
  for (const Point* p = begin; p != end; ++p) {
    const double d2 = (p->point - c.point).squaredNorm();
    if (d2 < best_d2 || (best != nullptr && d2 == best_d2 && p->feature < best->feature)) {
      best_d2 = d2;
      best = p;
    }
  }
  return best != nullptr ? &best->lambda : nullptr;
}

void PersistentContacts::OrderPairs() {
  int runs = 1;
  for (size_t i = 1; i < pairs_.size(); ++i) runs += pairs_[i - 1] < pairs_[i] ? 0 : 1;
  if (runs == 1) return;
  if (runs > kMergedRuns) {
    // not the detectors' order: sorted whole (stable: a repeated pair's
    // records stay in contact order)
    std::stable_sort(pairs_.begin(), pairs_.end());
  } else {
    MergeRuns();
  }
  for (size_t i = 1; i < pairs_.size(); ++i) {
    if (!(pairs_[i - 1] < pairs_[i])) {
      JoinRepeatedPairs();
      return;
    }
  }
}

void PersistentContacts::MergeRuns() {
  for (size_t i = 1; i < pairs_.size();) {
    if (pairs_[i - 1] < pairs_[i]) {
      ++i;
      continue;
    }
    // a run starts at i: merged into the ordered pairs before it, the
    // earlier first where a pair repeats (std::merge is stable)
    size_t j = i + 1;
    while (j < pairs_.size() && pairs_[j - 1] < pairs_[j]) ++j;
    merged_.clear();
    std::merge(pairs_.begin(), pairs_.begin() + i, pairs_.begin() + i, pairs_.begin() + j, std::back_inserter(merged_));
    std::copy(merged_.begin(), merged_.end(), pairs_.begin());
    i = j;
  }
}

void PersistentContacts::JoinRepeatedPairs() {
  joined_.clear();
  size_t out = 0;
  for (size_t i = 0; i < pairs_.size();) {
    Pair joint{pairs_[i].a, pairs_[i].b, static_cast<uint32_t>(joined_.size()), 0};
    for (; i < pairs_.size() && pairs_[i].a == joint.a && pairs_[i].b == joint.b; ++i) {
      const auto first = points_.begin() + pairs_[i].first;
      joined_.insert(joined_.end(), first, first + pairs_[i].count);
      joint.count += pairs_[i].count;
    }
    pairs_[out++] = joint;
  }
  pairs_.resize(out);
  points_.swap(joined_);
}

std::string PersistentContacts::Save() const {
  std::vector<SavedImpulse> saved;
  saved.reserve(points_.size());
  std::vector<uint32_t> order;
  for (const Pair& pair : pairs_) {
    order.resize(pair.count);
    for (uint32_t k = 0; k < pair.count; ++k) order[k] = pair.first + k;
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t i, uint32_t j) { return points_[i].feature < points_[j].feature; });
    for (uint32_t k : order) saved.push_back({pair.a, pair.b, points_[k].feature, points_[k].lambda, points_[k].point});
  }
  ByteWriter out;
  PutSavedImpulses(saved, &out);
  return out.bytes();
}

bool PersistentContacts::Restore(const std::string& bytes) {
  std::vector<SavedImpulse> saved;
  ByteReader in(bytes);
  if (!GetSavedImpulses(&in, &saved) || !in.done()) return false;
  // WarmStartCache::Restore's order: by pair and feature, then as saved
  std::stable_sort(saved.begin(), saved.end(), [](const SavedImpulse& x, const SavedImpulse& y) {
    return std::tie(x.a, x.b, x.feature) < std::tie(y.a, y.b, y.feature);
  });
  Clear();
  for (const SavedImpulse& s : saved) {
    Contact c;
    c.id_a = s.a;
    c.id_b = s.b;
    c.feature_id = s.feature;
    c.point = s.point;
    Add(c, s.lambda);
  }
  return true;
}

}  // namespace contactsim
