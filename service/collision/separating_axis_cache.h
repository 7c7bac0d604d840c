// Separating-axis cache (Baraff, "Curved surfaces and coherence for
// non-penetrating rigid body simulation", SIGGRAPH 1990; Baraff 1993): between
// steps bodies move little, so the face or edge pair that separated two
// polyhedra last step usually still does. The cache remembers it per body
// pair; the narrowphase tests it first and runs the full separating-axis test
// only when it no longer separates (a miss).
//
// A hit must cost far less than the full test, so the cached axis is tested
// on the bodies' own (body-frame) geometry: only the axis is rotated, into
// each body's frame, and each body's support along it is taken there (a box
// in closed form, a hull over its vertices); nothing is posed.
//
// Entries sit in one vector sorted by the pair's ids, found by binary
// search: the narrowphase looks pairs up in the broadphase's sorted order,
// so consecutive searches share their path and stay in cache (an ordered
// map's nodes, spread over the heap, cost a tenth of a 1,000-box step in
// cache misses). A detection replaces the whole vector (Rebuild) with the
// entries of its candidate pairs: a pair that stops being a candidate loses
// its axis and pays one full test if it comes back, which changes no result.
// Nothing depends on hashing or addresses (docs/architecture.md,
// determinism); Clear() drops every entry.
//
// Pairs collided in parallel (docs/architecture.md, "Threads") only read the
// cache (Separates, Find: const, so safe from many threads at once) and
// write what they would change into their own AxisCacheUpdate, from which
// the narrowphase rebuilds the cache afterwards in pair order. Each candidate pair is one
// key and appears once per detection, so deferring its write changes
// nothing that a later pair of the same detection reads.
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/polyhedron_sat.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// One pair's change to the cache and its hit or miss, recorded while the
// cache is only read and applied by SeparatingAxisCache::Apply.
struct AxisCacheUpdate {
  enum class Kind { kNone, kStore, kErase };
  Kind kind = Kind::kNone;
  BodyId a = 0, b = 0;  // the ordered pair the change is for
  SeparatingAxis axis;  // for kStore
  int hits = 0;         // Separates calls that returned true
  int misses = 0;       // and false

  void Store(BodyId id_a, BodyId id_b, const SeparatingAxis& stored) {
    kind = Kind::kStore;
    a = id_a;
    b = id_b;
    axis = stored;
  }
  void Erase(BodyId id_a, BodyId id_b) {
    kind = Kind::kErase;
    a = id_a;
    b = id_b;
  }
};

class SeparatingAxisCache {
 public:
  // True when the axis stored for bodies a and b (box or convex) separates
  // them by more than `margin` (m) at their current poses; false when there
  // is none or it no longer separates. Reads only; counts nothing.
  bool Separates(const RigidBody& a, const RigidBody& b, double margin) const;
  // The same, giving the axis that still separates, or nullptr.
  const SeparatingAxis* StillSeparatingAxis(const RigidBody& a, const RigidBody& b, double margin) const;

  // Separates, counting the outcome: true is a hit, false a miss.
  bool StillSeparates(const RigidBody& a, const RigidBody& b, double margin);

  // The axis stored for the ordered pair (a, b), or nullptr.
  const SeparatingAxis* Find(BodyId a, BodyId b) const;
  void Store(BodyId a, BodyId b, const SeparatingAxis& axis);
  void Erase(BodyId a, BodyId b);
  // Stores or erases as `update` says and adds its hits and misses.
  void Apply(const AxisCacheUpdate& update);
  // Replaces every entry by the outcome of one detection, `updates` holding
  // one per candidate pair: kStore keeps its axis (a hit stores the axis
  // it found), anything else leaves the pair out; adds their hits and
  // misses.
  void Rebuild(const std::vector<AxisCacheUpdate>& updates);

  // Lookups whose axis still separated (hits) and did not (misses), counted
  // by StillSeparates and Apply.
  int64_t hits() const { return hits_; }
  int64_t misses() const { return misses_; }
  size_t size() const { return entries_.size(); }

  // Forgets every axis and zeroes the counters.
  void Clear();

 private:
  struct Entry {
    BodyId a = 0, b = 0;
    SeparatingAxis axis;
    bool operator<(const Entry& o) const { return a != o.a ? a < o.a : b < o.b; }
  };
  std::vector<Entry> entries_;  // sorted by (a, b), no key twice
  std::vector<Entry> next_;     // Rebuild's, kept for its capacity
  // The place of (a, b) in entries_: its entry, or where it would go.
  size_t Place(BodyId a, BodyId b) const;
  bool At(size_t place, BodyId a, BodyId b) const {
    return place < entries_.size() && entries_[place].a == a && entries_[place].b == b;
  }
  int64_t hits_ = 0;
  int64_t misses_ = 0;
};

}  // namespace contactsim
