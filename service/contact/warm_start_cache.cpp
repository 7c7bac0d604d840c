#include "service/contact/warm_start_cache.h"

#include <algorithm>
#include <functional>

#include "service/collision/parallel_sort.h"
#include "service/contact/saved_impulses.h"
#include "service/physics/byte_stream.h"

namespace contactsim {
namespace {

// contacts a thread looks up at a time
constexpr int kWarmStartGrain = 256;
// contacts a thread turns into entries, and entries it sorts as one run,
// at a time (StoreEntries)
constexpr int kStoreGrain = 1024;

// The friction impulse of rows t1, t2 (directions lin_b) in the contact
// frame's tangents t1f, t2f (PerpendicularBasis of the normal) and back:
// Lemke's rows turn with the slip (lcp_contact_rows.h), the cache keeps the
// frame that depends only on n. Rows already in that frame pass unchanged.
void ToFrame(const Vec3& n, const ConstraintRow& r1, const ConstraintRow& r2, double* l1, double* l2) {
  Vec3 t1f, t2f;
  PerpendicularBasis(n, &t1f, &t2f);
  if (r1.lin_b == t1f && r2.lin_b == t2f) return;
  const Vec3 f = *l1 * r1.lin_b + *l2 * r2.lin_b;
  *l1 = f.dot(t1f);
  *l2 = f.dot(t2f);
}

void FromFrame(const Vec3& n, const ConstraintRow& r1, const ConstraintRow& r2, double* l1, double* l2) {
  Vec3 t1f, t2f;
  PerpendicularBasis(n, &t1f, &t2f);
  if (r1.lin_b == t1f && r2.lin_b == t2f) return;
  const Vec3 f = *l1 * t1f + *l2 * t2f;
  *l1 = f.dot(r1.lin_b);
  *l2 = f.dot(r2.lin_b);
}

}  // namespace

void WarmStartCache::Load(const ContactSet& contacts, std::vector<ConstraintRow>* rows, ParallelRunner* runner) const {
  const auto load = [&](int begin, int end, int /*worker*/) {
    size_t hint = 0;
    for (int k = begin; k < end; ++k) {
      const Contact& c = contacts[k];
      const std::array<double, 3>* cached = Find(c, &hint);
      const bool found = cached != nullptr;
      for (int j = 0; j < 3; ++j) (*rows)[3 * k + j].lambda = found ? (*cached)[j] : 0.0;
      ConstraintRow& r1 = (*rows)[3 * k + 1];
      ConstraintRow& r2 = (*rows)[3 * k + 2];
      if (found) FromFrame(c.normal, r1, r2, &r1.lambda, &r2.lambda);
    }
  };
  const int n = static_cast<int>(contacts.size());
  if (runner == nullptr) {
    load(0, n, 0);
  } else {
    runner->For(n, kWarmStartGrain, load);
  }
}

void WarmStartCache::Store(const ContactSet& contacts, const std::vector<ConstraintRow>& rows,
                           ParallelRunner* runner) {
  StoreEntries(contacts.size(), [&](size_t k, Entry* entry) {
    const Contact& c = contacts[k];
    if (rows[3 * k].lambda <= 0.0) return false;
    double l1 = rows[3 * k + 1].lambda, l2 = rows[3 * k + 2].lambda;
    ToFrame(c.normal, rows[3 * k + 1], rows[3 * k + 2], &l1, &l2);
    *entry = {Key{c.id_a, c.id_b, c.feature_id}, {rows[3 * k].lambda, l1, l2}, c.point, k};
    return true;
  }, runner);
}

void WarmStartCache::StoreEntries(size_t n, const MakeEntry& make, ParallelRunner* runner) {
  const auto split = [runner](int count, int grain, const ParallelRunner::RangeFn& body) {
    if (runner == nullptr) {
      body(0, count, 0);
    } else {
      runner->For(count, grain, body);
    }
  };
  // each contact writes its own slot, kept or not; the kept ones are then
  // packed in contact order
  scratch_.resize(n);
  kept_.assign(n, 0);
  split(static_cast<int>(n), kStoreGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) kept_[k] = make(k, &scratch_[k]) ? 1 : 0;
  });
  impulses_.clear();
  for (size_t k = 0; k < n; ++k) {
    if (kept_[k] != 0) impulses_.push_back(scratch_[k]);
  }
  // the entries' order is total (key, then contact index), so the sort on
  // the threads gives what one std::sort gives, bit for bit
  // (parallel_sort.h). Contacts come pair by pair in body order, so
  // neighbouring runs are mostly in order already and their merge is
  // skipped.
  ParallelSort(&impulses_, &scratch_, runner, kStoreGrain, std::less<Entry>());
}

size_t WarmStartCache::PairStart(const Contact& c, size_t* hint) const {
  // contacts come pair by pair: find where the pair's entries start once
  // (bisection) and keep it while the pair's contacts follow
  const size_t at = *hint;
  const bool same_pair = at < impulses_.size() && std::get<0>(impulses_[at].key) == c.id_a &&
                         std::get<1>(impulses_[at].key) == c.id_b &&
                         (at == 0 || std::get<0>(impulses_[at - 1].key) != c.id_a ||
                          std::get<1>(impulses_[at - 1].key) != c.id_b);
  if (!same_pair) {
    const Entry probe{Key{c.id_a, c.id_b, 0}, {}, Vec3::Zero(), 0};
    *hint = static_cast<size_t>(std::lower_bound(impulses_.begin(), impulses_.end(), probe) - impulses_.begin());
  }
  return *hint;
}

const std::array<double, 3>* WarmStartCache::Find(const Contact& c, size_t* hint) const {
  // the pair's few entries, sorted by feature, then order, so the first
  // match is the one a bisection would find
  const size_t first = PairStart(c, hint);
  const Key key{c.id_a, c.id_b, c.feature_id};
  for (size_t k = first; k < impulses_.size(); ++k) {
    const Key& at = impulses_[k].key;
    if (std::get<0>(at) != c.id_a || std::get<1>(at) != c.id_b || std::get<2>(at) > c.feature_id) break;
    if (at == key) return &impulses_[k].lambda;
  }
  const Entry* near = Near(c, first);
  return near != nullptr ? &near->lambda : nullptr;
}

const WarmStartCache::Entry* WarmStartCache::Near(const Contact& c, size_t pair_first) const {
  const Entry* best = nullptr;
  double best_d2 = kNearMatchDistance * kNearMatchDistance;
  for (size_t k = pair_first; k < impulses_.size(); ++k) {
    const Entry& e = impulses_[k];
    if (std::get<0>(e.key) != c.id_a || std::get<1>(e.key) != c.id_b) break;
    const double d2 = (e.point - c.point).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = &e;
    }
  }
  return best;
}

void WarmStartCache::StoreFrame(const ContactSet& contacts, const std::vector<std::array<double, 3>>& impulses,
                                ParallelRunner* runner) {
  StoreEntries(contacts.size(), [&](size_t k, Entry* entry) {
    const Contact& c = contacts[k];
    if (impulses[k][0] <= 0.0) return false;
    *entry = {Key{c.id_a, c.id_b, c.feature_id}, impulses[k], c.point, k};
    return true;
  }, runner);
}

void WarmStartCache::LoadJoints(const std::vector<JointBlock>& blocks, size_t first_row,
                                std::vector<ConstraintRow>* rows) const {
  for (const JointBlock& blk : blocks) {
    for (int r = 0; r < blk.count; ++r) {
      ConstraintRow& row = (*rows)[first_row + blk.first + r];
      const auto it = std::lower_bound(joint_impulses_.begin(), joint_impulses_.end(),
                                       std::make_pair(JointKey{blk.id, r}, -ConstraintRow::kInf));
      const bool found = it != joint_impulses_.end() && it->first == JointKey{blk.id, r};
      if (found) row.lambda = std::clamp(it->second, row.lo, row.hi);
    }
  }
}

void WarmStartCache::StoreJoints(const std::vector<JointBlock>& blocks, size_t first_row,
                                 const std::vector<ConstraintRow>& rows) {
  joint_impulses_.clear();
  for (const JointBlock& blk : blocks) {
    for (int r = 0; r < blk.count; ++r) {
      joint_impulses_.push_back({JointKey{blk.id, r}, rows[first_row + blk.first + r].lambda});
    }
  }
  std::sort(joint_impulses_.begin(), joint_impulses_.end());
}

// Layout: the contact entries (saved_impulses.h); then, when there are
// joint rows, their count and entries (snapshots written before joints end
// after the contacts).
std::string WarmStartCache::Save() const {
  std::vector<SavedImpulse> saved;
  saved.reserve(impulses_.size());
  for (const Entry& e : impulses_) {
    saved.push_back({std::get<0>(e.key), std::get<1>(e.key), std::get<2>(e.key), e.lambda, e.point});
  }
  ByteWriter out;
  PutSavedImpulses(saved, &out);
  if (!joint_impulses_.empty()) {
    out.Put(static_cast<uint64_t>(joint_impulses_.size()));
    for (const auto& [key, lambda] : joint_impulses_) {
      out.Put(key.first);
      out.Put(key.second);
      out.Put(lambda);
    }
  }
  return out.bytes();
}

bool WarmStartCache::Restore(const std::string& bytes) {
  std::vector<SavedImpulse> saved;
  ByteReader in(bytes);
  bool ok = GetSavedImpulses(&in, &saved);
  std::vector<Entry> loaded;
  for (size_t i = 0; ok && i < saved.size(); ++i) {
    const SavedImpulse& s = saved[i];
    loaded.push_back({Key{s.a, s.b, s.feature}, s.lambda, s.point, i});
  }
  std::vector<std::pair<JointKey, double>> joints;
  uint64_t m = 0;
  if (ok && !in.done()) ok = in.Get(&m);
  for (uint64_t i = 0; ok && i < m; ++i) {
    JointKey key;
    double lambda = 0.0;
    ok = in.Get(&key.first) && in.Get(&key.second) && in.Get(&lambda);
    joints.push_back({key, lambda});
  }
  if (!ok || !in.done()) return false;
  std::sort(loaded.begin(), loaded.end());
  std::sort(joints.begin(), joints.end());
  impulses_ = std::move(loaded);
  joint_impulses_ = std::move(joints);
  return true;
}

}  // namespace contactsim
