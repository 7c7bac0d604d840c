// Which pairs of bodies may touch: the one predicate every pair search asks
// (the collision detector's broadphase pairs, barrier's primitive search,
// the sleep wrapper's wake test), so that a filtered pair yields no contact
// under any method and never joins two islands.
//
// Per body, Box2D's b2Filter (and Bullet's group/mask): a category (the bits
// the body is), a mask (the bits it touches) and a group. Two bodies of the
// same nonzero group always touch when the group is positive and never when
// it is negative; otherwise they touch when (cat_A & mask_B) != 0 and
// (cat_B & mask_A) != 0 (Box2D, b2_fixture.h, b2ContactFilter::ShouldCollide).
// Per joint, Box2D's collideConnected: the two bodies of a joint that does
// not allow it never touch, whatever their filters say (as Box2D's
// b2Body::ShouldCollide runs before the filter; PyBullet and Drake likewise
// exclude the links a joint connects).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>

#include "service/physics/rigid_body.h"

namespace contactsim {

// The ordered id pairs of bodies held together by a joint that excludes
// their contacts, with how many such joints each pair has (removing one of
// two joints keeps the pair excluded). Lookups only; nothing iterates it, so
// its order never reaches the engine's results.
class JointPairSet {
 public:
  void Add(BodyId a, BodyId b);
  void Remove(BodyId a, BodyId b);
  bool Contains(BodyId a, BodyId b) const {
    return !count_.empty() && count_.find(Key(a, b)) != count_.end();
  }
  bool empty() const { return count_.empty(); }
  size_t size() const { return count_.size(); }
  void Clear() { count_.clear(); }

 private:
  using PairKey = std::pair<BodyId, BodyId>;
  struct Hash {
    size_t operator()(const PairKey& k) const {
      // the two ids mixed as boost::hash_combine does
      size_t h = std::hash<BodyId>()(k.first);
      return h ^ (std::hash<BodyId>()(k.second) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
    }
  };
  static PairKey Key(BodyId a, BodyId b) { return a < b ? PairKey(a, b) : PairKey(b, a); }
  std::unordered_map<PairKey, int, Hash> count_;
};

// Box2D's group and category/mask test of two bodies' filters.
inline bool FiltersAccept(const RigidBody& a, const RigidBody& b) {
  if (a.collision_group == b.collision_group && a.collision_group != 0) return a.collision_group > 0;
  return (a.collision_category & b.collision_mask) != 0 && (b.collision_category & a.collision_mask) != 0;
}

// True when bodies a and b may touch: not held by a joint that excludes
// their contacts, and accepted by their filters.
inline bool ShouldCollide(const RigidBody& a, const RigidBody& b, const JointPairSet& joined) {
  return FiltersAccept(a, b) && !joined.Contains(a.id, b.id);
}

// True when the body's filter is the default one (category 1, every mask
// bit, group 0), which touches every other default body.
inline bool HasDefaultFilter(const RigidBody& b) {
  return b.collision_category == 1u && b.collision_mask == 0xFFFFFFFFu && b.collision_group == 0;
}

}  // namespace contactsim
