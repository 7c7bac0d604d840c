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
// Keys are ordered maps of body ids, so iteration and memory use do not depend
// on hashing (docs/architecture.md, determinism). Ids are never reused, so an entry
// of a removed body is never looked up again; Clear() drops them all.
//
// Pairs collided in parallel (docs/architecture.md, "Threads") only read the
// cache (Separates, Find: const, so safe from many threads at once) and
// write what they would change into their own AxisCacheUpdate, which the
// narrowphase applies afterwards in pair order. Each candidate pair is one
// key and appears once per detection, so deferring its write changes
// nothing that a later pair of the same detection reads.
#pragma once

#include <cstdint>
#include <map>
#include <utility>

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

  // Separates, counting the outcome: true is a hit, false a miss.
  bool StillSeparates(const RigidBody& a, const RigidBody& b, double margin);

  // The axis stored for the ordered pair (a, b), or nullptr.
  const SeparatingAxis* Find(BodyId a, BodyId b) const;
  void Store(BodyId a, BodyId b, const SeparatingAxis& axis);
  void Erase(BodyId a, BodyId b);
  // Stores or erases as `update` says and adds its hits and misses.
  void Apply(const AxisCacheUpdate& update);

  // Lookups whose axis still separated (hits) and did not (misses), counted
  // by StillSeparates and Apply.
  int64_t hits() const { return hits_; }
  int64_t misses() const { return misses_; }
  size_t size() const { return axes_.size(); }

  // Forgets every axis and zeroes the counters.
  void Clear();

 private:
  std::map<std::pair<BodyId, BodyId>, SeparatingAxis> axes_;
  int64_t hits_ = 0;
  int64_t misses_ = 0;
};

}  // namespace contactsim
