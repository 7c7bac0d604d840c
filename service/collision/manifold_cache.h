// Manifold reuse: a touching pair of polyhedra keeps its contact points in
// the two bodies' frames, and while body B has moved little in A's frame
// since they were made, each point's world position, normal and depth are
// recomputed from the current poses instead of running the separating-axis
// test and clipping again (the persistent manifolds of Bullet's
// btPersistentManifold::refreshContactPoints and PhysX's contact cache, here
// with a bound on the relative motion instead of per-point breaking tests).
//
// What is reused is exact where it matters: a point is a material point of
// A's surface and one of B's, so its depth, their distance along the stored
// normal, follows the bodies; only the choice of points (the clip and the
// reduction) and the normal's direction are those of the pose the manifold
// was made at. The reuse bound keeps that pose near: every point of B has
// moved by at most |dp| + 2 sin(dtheta / 2) r_B in A's frame (dp, dtheta the
// change of B's position and rotation in A's frame, r_B the farthest point
// of B from its origin), and the manifold is reused while that is at most
// kManifoldReuseFraction of the detection's margin. A feature the manifold
// left out was farther than the margin when it was made, so it is still
// farther than (1 - kManifoldReuseFraction) margin: reuse never hides an
// overlap, only a far speculative point (docs/physics.md, "Collision").
//
// Entries sit in one vector sorted by the pair's ids and are rebuilt at
// each detection from its candidate pairs, in pair order, from per-pair
// updates written aside as the separating-axis cache does
// (separating_axis_cache.h): pairs may run on any number of threads with
// the same result, and reuse depends only on the poses, never on timing.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "service/collision/contact.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// Whether the detector reuses manifolds unless told otherwise (the server's
// `manifold_reuse` option): on; snapshots carry the kept manifolds
// (service/scene/snapshot_manifolds.h), so a restored run continues bit for
// bit, and BENCHMARKS.md ("Shared: manifold reuse") measures what it saves.
constexpr bool kManifoldReuseDefault = true;
// The share of the detection's margin that B's points may move in A's frame
// before the manifold is made again: 1 mm at soft's 1 cm margin, 0.1 mm at
// impulse's and lcp's 1 mm slop. A resting box moves micrometres in its
// neighbour's frame; a landing or sliding one exceeds it within a step.
constexpr double kManifoldReuseFraction = 0.1;
// Points of a kept manifold at most: polyhedron manifolds are reduced to four.
constexpr int kMaxCachedPoints = 4;

// One contact point in the bodies' own frames.
struct CachedPoint {
  Vec3 on_a_A = Vec3::Zero();    // m, the point of A's surface, in A's frame
  Vec3 on_b_B = Vec3::Zero();    // m, the point of B's surface, in B's frame
  Vec3 normal_A = Vec3::UnitZ(); // unit, from A to B, in A's frame
  uint32_t feature_id = 0;
};

// One pair's manifold and the pose of B in A's frame it was made at.
struct CachedManifold {
  BodyId a = 0, b = 0;
  Vec3 p_AB = Vec3::Zero();  // m, B's origin in A's frame
  Quat q_AB = Quat::Identity();
  double reach_b = 0.0;      // m, B's farthest point from its origin
  int count = 0;
  std::array<CachedPoint, kMaxCachedPoints> points;
  bool operator<(const CachedManifold& o) const { return a != o.a ? a < o.a : b < o.b; }
};

// One pair's outcome, written while the cache is only read and applied by
// ManifoldCache::Rebuild in pair order.
struct ManifoldUpdate {
  enum class Kind { kNone, kKeep, kStore };
  Kind kind = Kind::kNone;
  size_t kept = 0;           // kKeep: the entry's place in the cache
  CachedManifold manifold;   // kStore
  int reuses = 0;            // Reuse calls that appended the kept points
  int remakes = 0;           // and that found none to keep
};

// True for the pairs whose manifolds are kept: two polyhedra (box, convex).
bool KeepsManifold(const RigidBody& a, const RigidBody& b);

// True when `entries` are sorted by (a, b) with no key twice, as a cache holds them.
bool IsSortedByPair(const std::vector<CachedManifold>& entries);

class ManifoldCache {
 public:
  // When a manifold is kept for (a, b) and B has moved less than
  // kManifoldReuseFraction * margin in A's frame since it was made, appends
  // its points at the current poses (those with depth > -margin; a, b their
  // indices) to `out`, marks the entry kept in `update` and returns true.
  // Otherwise appends nothing and returns false. Reads only.
  bool Reuse(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ManifoldUpdate* update,
             ContactSet* out) const {
    return ReuseAt(Find(a.id, b.id), a, ia, b, ib, margin, update, out);
  }
  // The same with the pair's entry found beforehand (Locate; null: none).
  bool ReuseAt(const CachedManifold* m, const RigidBody& a, int ia, const RigidBody& b, int ib, double margin,
               ManifoldUpdate* update, ContactSet* out) const;
  // The entry of each pair (indices into `bodies`, keyed by the two ids) or
  // null, into `found`: the same as Find on each, by one merge of the pairs
  // with the sorted entries while the pairs' ids ascend (the broadphase
  // sorts pairs by index, which follows the ids in most worlds) and by
  // Find for the rest. Reads only.
  void Locate(const std::vector<RigidBody>& bodies, const std::vector<std::pair<int, int>>& pairs,
              std::vector<const CachedManifold*>* found) const;
  // Writes into `update` the manifold of contacts [first, first + count)
  // that Collide just made for (a, b), to keep; none when there are no
  // points or more than kMaxCachedPoints.
  static void Record(const RigidBody& a, const RigidBody& b, const Contact* first, int count,
                     ManifoldUpdate* update);
  // Replaces every entry by the outcome of one detection (one update per
  // candidate pair): kKeep and kStore keep a manifold, kNone drops the pair.
  void Rebuild(const std::vector<ManifoldUpdate>& updates);

  const CachedManifold* Find(BodyId a, BodyId b) const;
  size_t size() const { return entries_.size(); }
  // Every kept manifold, sorted by (a, b): the state a snapshot saves
  // (service/scene/snapshot_manifolds.h).
  const std::vector<CachedManifold>& entries() const { return entries_; }
  // Replaces every manifold by a snapshot's, which must be sorted by (a, b)
  // with no key twice (IsSortedByPair); the counters stay.
  void Restore(std::vector<CachedManifold> entries);
  int64_t reuses() const { return reuses_; }
  int64_t remakes() const { return remakes_; }
  // Forgets every manifold and zeroes the counters.
  void Clear();

 private:
  std::vector<CachedManifold> entries_;  // sorted by (a, b), no key twice
  std::vector<CachedManifold> next_;     // Rebuild's, kept for its capacity
  size_t Place(BodyId a, BodyId b) const;
  int64_t reuses_ = 0;
  int64_t remakes_ = 0;
};

}  // namespace contactsim
