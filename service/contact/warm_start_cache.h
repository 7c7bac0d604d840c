// Last step's contact impulses, kept per contact feature so that the next
// solve starts from them (warm starting, Catto 2005); shared by the impulse,
// lcp and soft methods (impulse keeps forces, impulse / h). Key: (id of A, id of
// B, feature id), in a vector sorted by key and searched by bisection
// (deterministic, and no allocation once its capacity is reached); contact
// pairs come in a canonical body order (docs/conventions.md), so A and B do
// not swap between steps. Three rows per contact: normal, t1, t2; the
// friction impulse is kept in the tangents of the contact frame
// (PerpendicularBasis of the normal), whatever the rows' tangents.
// A contact whose feature id is not in the cache takes the impulses of the
// pair's cached point nearest to it within kNearMatchDistance, if any: two
// faces lying exactly flush clip to the same corners by other features from
// one step to the next (an incident vertex one step, an incident edge cut by
// a side plane the next), and starting those corners from zero while their
// neighbours keep their impulses tilts a resting box (docs/physics.md,
// "Warm starting"). Contact points keep their place from step to step
// (Jolt's contact cache matches points by position likewise).
// Joint rows are kept too, per (joint id, row within the joint's block):
// the equality rows of a joint come in a fixed order (joint_rows.h), so a
// hanging chain starts each step from last step's tensions. A hinge limit
// row (the last of its block, present only near the limit) takes its cached
// impulse clamped to its current bounds.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "service/collision/contact.h"
#include "service/collision/parallel_runner.h"
#include "service/contact/constraint_row.h"
#include "service/contact/joints/joint_rows.h"

namespace contactsim {

class WarmStartCache {
 public:
  // m: how far a point may lie from a cached one of its pair and still take
  // its impulses when its feature id changed (a resting contact moves by
  // much less in a step; distinct points of one manifold lie much farther
  // apart)
  static constexpr double kNearMatchDistance = 1e-3;

  // Sets the lambda of the three rows of each contact from the cache (0 when
  // absent); with a runner, the contacts split over its threads.
  void Load(const ContactSet& contacts, std::vector<ConstraintRow>* rows, ParallelRunner* runner = nullptr) const;
  // Replaces the cache by the rows' impulses; with a runner, the entries
  // are made and sorted on its threads (the same cache bit for bit: the
  // entries' order is total, StoreEntries).
  void Store(const ContactSet& contacts, const std::vector<ConstraintRow>& rows, ParallelRunner* runner = nullptr);
  // The same for solvers that keep their impulses in the contact frame
  // (normal, t1, t2 of PerpendicularBasis): Find gives contact c's cached
  // impulses or nullptr; StoreFrame keeps impulses[k] for contacts[k] when
  // its normal impulse is positive.
  const std::array<double, 3>* Find(const Contact& c) const { return Find(c, &cursor_); }
  // The same with the caller's search hint (where the last pair looked up
  // starts), for lookups split over threads: a hint moves where a search
  // starts, never what it finds.
  const std::array<double, 3>* Find(const Contact& c, size_t* hint) const;
  void StoreFrame(const ContactSet& contacts, const std::vector<std::array<double, 3>>& impulses,
                  ParallelRunner* runner = nullptr);
  // The same for joint rows: blocks index rows from `first_row` on; a row
  // with no cached impulse (a new joint) keeps the lambda it came with.
  void LoadJoints(const std::vector<JointBlock>& blocks, size_t first_row, std::vector<ConstraintRow>* rows) const;
  void StoreJoints(const std::vector<JointBlock>& blocks, size_t first_row, const std::vector<ConstraintRow>& rows);
  void Clear() {
    impulses_.clear();
    joint_impulses_.clear();
  }
  // The impulses bit for bit, for snapshots (ContactMethod::SaveState).
  std::string Save() const;
  // Replaces the impulses by saved ones; false (and nothing changed) when
  // the bytes are malformed.
  bool Restore(const std::string& bytes);
  size_t size() const { return impulses_.size(); }
  size_t joint_rows() const { return joint_impulses_.size(); }

 private:
  using Key = std::tuple<BodyId, BodyId, uint32_t>;
  struct Entry {
    Key key;
    std::array<double, 3> lambda;
    Vec3 point;    // m, world, where the contact was
    size_t order;  // contact index: of two contacts with one key (a hash collision) the first wins
    bool operator<(const Entry& o) const { return std::tie(key, order) < std::tie(o.key, o.order); }
  };
  // the entry of c's pair nearest to c.point within kNearMatchDistance, or
  // nullptr; `pair_first` is where the pair's entries start
  const Entry* Near(const Contact& c, size_t pair_first) const;
  size_t PairStart(const Contact& c, size_t* hint) const;
  // Replaces impulses_ by the entries make(k, &entry) returns true for, k
  // over [0, n), sorted; on the runner's threads when given.
  using MakeEntry = std::function<bool(size_t k, Entry* entry)>;
  void StoreEntries(size_t n, const MakeEntry& make, ParallelRunner* runner);

  std::vector<Entry> impulses_;
  std::vector<Entry> scratch_;  // StoreEntries' slots and merge buffer
  std::vector<char> kept_;      // StoreEntries: per contact, whether it is kept
  mutable size_t cursor_ = 0;  // where the pair Find looked up last starts (a search hint only)
  // (joint id, row within the block) -> lambda, sorted by key
  using JointKey = std::pair<JointId, int32_t>;
  std::vector<std::pair<JointKey, double>> joint_impulses_;
};

}  // namespace contactsim
