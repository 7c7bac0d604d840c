// Last step's contacts, pair by pair, each point with its feature id, place
// and impulses in the contact frame (normal, t1, t2 of PerpendicularBasis),
// for the next step's warm start (Catto 2005): the contacts persist as
// Box3D's and Bullet's manifolds do, instead of a cache of entries looked up
// by key and sorted every step (warm_start_cache.h).
//
// The matching is WarmStartCache's (docs/physics.md, "Warm starting"), so
// either gives a contact the same impulses: last step's point of the same
// body pair (A and B as the detector orders them) with the same feature id,
// the first in contact order when two share one; else the pair's point
// nearest within WarmStartCache::kNearMatchDistance, of two as near the one
// with the smaller feature id, then the first in contact order. Only points
// that pushed (normal impulse > 0) are kept.
//
// Why no lookup: the detector gives contacts pair by pair in body order
// (broadphase.h), and the ids ascend with the body index (World::AddBody),
// so last step's pairs, kept in that order, and this step's meet as two
// sorted lists: a walk forward finds each pair, and a point among its
// pair's few by feature id. DetectAhead appends its fast pairs' contacts
// after the others (two ascending runs): the walk starts over with a
// bisection where the pairs' order steps back, and Keep merges the runs
// of pair records (and sorts them where more came: not the detectors'
// order). Any order of contacts gives the same matches.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "service/collision/contact.h"

namespace contactsim {

class PersistentContacts {
 public:
  // Calls take(k, impulses) for each contact k of [begin, end) that finds
  // last step's impulses; chunks may run on different threads (the walk is
  // each chunk's own).
  template <typename Take>
  void Match(const ContactSet& contacts, int begin, int end, const Take& take) const;
  // Replaces the kept contacts by `contacts`, impulse_of(k) giving contact
  // k's impulses (std::array<double, 3>, the contact frame's).
  template <typename ImpulseOf>
  void Keep(const ContactSet& contacts, const ImpulseOf& impulse_of);
  void Clear() {
    pairs_.clear();
    points_.clear();
  }
  // WarmStartCache::Save's bytes for the same impulses (its entries by
  // pair, feature, contact), so snapshots read either way.
  std::string Save() const;
  // Replaces the contacts by saved ones; false (and nothing changed) when
  // the bytes are malformed.
  bool Restore(const std::string& bytes);
  size_t size() const { return points_.size(); }

 private:
  struct Point {
    uint32_t feature;
    std::array<double, 3> lambda;
    Vec3 point;  // m, world, where the contact was
  };
  struct Pair {
    BodyId a, b;
    uint32_t first, count;  // its points in points_
    bool operator<(const Pair& o) const { return a < o.a || (a == o.a && b < o.b); }
  };
  // where a walk over the pairs stands: the pair it looked for last, and
  // the first kept pair not before it
  struct Walk {
    Pair last{};
    size_t at = 0;
    bool started = false;
  };
  // c's pair, walking on from where the last one was, or nullptr
  const Pair* FindPair(const Contact& c, Walk* walk) const;
  // c's impulses among its pair's points, or nullptr: by feature id here,
  // by place (Nearest) where the id is new
  const std::array<double, 3>* FindPoint(const Pair& pair, const Contact& c) const {
    const Point* begin = points_.data() + pair.first;
    for (const Point* p = begin; p != begin + pair.count; ++p) {
      if (p->feature == c.feature_id) return &p->lambda;
    }
    return Nearest(pair, c);
  }
  const std::array<double, 3>* Nearest(const Pair& pair, const Contact& c) const;
  void Add(const Contact& c, const std::array<double, 3>& lambda) {
    if (pairs_.empty() || pairs_.back().a != c.id_a || pairs_.back().b != c.id_b) {
      pairs_.push_back({c.id_a, c.id_b, static_cast<uint32_t>(points_.size()), 0});
    }
    points_.push_back({c.feature_id, lambda, c.point});
    ++pairs_.back().count;
  }
  // Puts the pairs in order: merges their ascending runs (each merge
  // passes over the pairs before it, so more than kMergedRuns runs are
  // sorted instead), and joins a pair's points that came apart (none from
  // the detectors).
  static constexpr int kMergedRuns = 8;
  void OrderPairs();
  void MergeRuns();
  void JoinRepeatedPairs();

  std::vector<Pair> pairs_;    // ascending, each once
  std::vector<Point> points_;  // a pair's together, in contact order
  std::vector<Pair> merged_;   // OrderPairs' buffer
  std::vector<Point> joined_;  // JoinRepeatedPairs' buffer
};

template <typename Take>
void PersistentContacts::Match(const ContactSet& contacts, int begin, int end, const Take& take) const {
  Walk walk;
  const Pair* pair = nullptr;
  for (int k = begin; k < end; ++k) {
    const Contact& c = contacts[k];
    if (k == begin || c.id_a != contacts[k - 1].id_a || c.id_b != contacts[k - 1].id_b) pair = FindPair(c, &walk);
    if (pair == nullptr) continue;
    if (const std::array<double, 3>* lambda = FindPoint(*pair, c)) take(k, *lambda);
  }
}

template <typename ImpulseOf>
void PersistentContacts::Keep(const ContactSet& contacts, const ImpulseOf& impulse_of) {
  Clear();
  for (size_t k = 0; k < contacts.size(); ++k) {
    const std::array<double, 3> lambda = impulse_of(k);
    if (lambda[0] > 0.0) Add(contacts[k], lambda);
  }
  OrderPairs();
}

}  // namespace contactsim
