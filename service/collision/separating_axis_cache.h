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
#pragma once

#include <cstdint>
#include <map>
#include <utility>

#include "service/collision/polyhedron_sat.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

class SeparatingAxisCache {
 public:
  // True (a hit) when the axis stored for bodies a and b (box or convex)
  // separates them by more than `margin` (m) at their current poses; false (a
  // miss) when there is none or it no longer separates. Counts the outcome.
  bool StillSeparates(const RigidBody& a, const RigidBody& b, double margin);

  // The axis stored for the ordered pair (a, b), or nullptr.
  const SeparatingAxis* Find(BodyId a, BodyId b) const;
  void Store(BodyId a, BodyId b, const SeparatingAxis& axis);
  void Erase(BodyId a, BodyId b);

  // Calls of StillSeparates that returned true (hits) and false (misses).
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
