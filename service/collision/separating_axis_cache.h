// Separating-axis cache (Baraff, "Curved surfaces and coherence for
// non-penetrating rigid body simulation", SIGGRAPH 1990; Baraff 1993): between
// steps bodies move little, so the face or edge pair that separated two
// polyhedra last step usually still does. The cache remembers it per body
// pair; the narrowphase tests it first and runs the full separating-axis test
// only when it no longer separates (a miss).
//
// Keys are ordered maps of body ids, so iteration and memory use do not depend
// on hashing (ARCHITECTURE.md, determinism). Ids are never reused, so an entry
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
  // The axis stored for the ordered pair (a, b), or nullptr.
  const SeparatingAxis* Find(BodyId a, BodyId b) const;
  void Store(BodyId a, BodyId b, const SeparatingAxis& axis);
  void Erase(BodyId a, BodyId b);

  // Hit: the cached axis still separated the pair. Miss: the full test ran.
  void CountHit() { ++hits_; }
  void CountMiss() { ++misses_; }
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
