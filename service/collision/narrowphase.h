// Narrowphase: contact points of one pair of bodies, looked up in a table by
// the two shape types (as MuJoCo's mjCOLLISIONFUNC).
//
// Conventions (contact.h, docs/conventions.md): normals are unit, world, from
// a to b; depth > 0 is penetration; a pair whose separation is below `margin`
// is also reported, with depth = -separation < 0 (speculative contacts, used
// for time-of-impact root finding, so the depth is continuous in the poses);
// points lie midway between the two surfaces. Swapping a and b gives the same
// points and feature ids with flipped normals.
#pragma once

#include <utility>
#include <vector>

#include "service/collision/broadphase.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/contact.h"
#include "service/collision/manifold_cache.h"
#include "service/collision/parallel_runner.h"
#include "service/collision/separating_axis_cache.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// Appends the contacts of bodies a and b (indices ia, ib in the world) with
// depth > -margin to `out`; normals point from a to b. Returns the number of
// contacts appended. Stateless: no separating-axis cache.
int Collide(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ContactSet* out);

// Signed distance of the pair (m) for time-of-impact searches: for two
// polyhedra (box, convex) the largest separation over all separating-axis
// candidates (a lower bound of the distance when apart, minus the exact
// penetration depth when overlapping); for other pairs minus the deepest
// contact's depth (exact). Values above `margin` are returned as `margin`
// (the pair is at least that far apart). Continuous in the poses and never
// above the true distance, so conservative advancement cannot step over a
// contact. `normal`, when given and the value is below `margin`, receives the
// unit direction (world, from a to b) of that distance: for two polyhedra the
// unbiased separating axis (the exact minimum-penetration direction when they
// overlap, where a manifold's normal may prefer a face, polyhedron_sat.h).
double PairSignedDistance(const RigidBody& a, const RigidBody& b, double margin, Vec3* normal = nullptr);

// The same, remembering per body pair the axis that separated two polyhedra
// (box, convex) so that the next call on a still-separated pair costs one axis
// instead of the full separating-axis test. Results are identical to the free
// function. A CollisionDetector owns one and calls it for every candidate pair.
class Narrowphase {
 public:
  int Collide(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ContactSet* out);
  // The same contacts as Collide, trying the stored axis first but leaving
  // the cache as it is: for a look at poses other than the detection's (an
  // impulse sub-step's end), where most pairs the detection found apart are
  // still apart along the same axis. Safe from many threads at once.
  int CollideReadOnly(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ContactSet* out) const;
  // Collides every pair (indices into `bodies`) and appends the contacts to
  // `out` in pair order: the same contacts as Collide on each pair in turn.
  // Each pair reads the cache and writes its change aside
  // (separating_axis_cache.h), and the cache is then rebuilt from the
  // changes in pair order, keeping only this detection's pairs; with more
  // than one thread each pair fills its own slot of contacts, and the slots
  // are concatenated in pair order, so cache, counters and contacts are the
  // same bit for bit for any number of threads.
  // With manifold reuse on, a touching pair of polyhedra whose relative
  // pose moved little since its manifold was made gets that manifold at the
  // current poses instead (manifold_cache.h); its kept manifolds are
  // rebuilt in pair order like the axes, so this too is the same for any
  // number of threads.
  void CollidePairs(const std::vector<RigidBody>& bodies, const std::vector<BodyPair>& pairs, double margin,
                    ParallelRunner& runner, ContactSet* out);
  // Manifold reuse in CollidePairs (the `manifold_reuse` option); off, every
  // pair is collided afresh. Switching forgets the kept manifolds.
  void SetManifoldReuse(bool on) {
    if (on != manifold_reuse_) manifolds_.Clear();
    manifold_reuse_ = on;
  }
  bool manifold_reuse() const { return manifold_reuse_; }
  // Replaces the kept manifolds by a snapshot's (ManifoldCache::Restore);
  // with reuse off there are none to keep, and they are dropped.
  void RestoreManifolds(std::vector<CachedManifold> entries) {
    if (manifold_reuse_) manifolds_.Restore(std::move(entries));
  }
  // Forgets the cached axes and manifolds and zeroes the counters (scene reset or load).
  void Reset() {
    cache_.Clear();
    manifolds_.Clear();
  }
  const SeparatingAxisCache& cache() const { return cache_; }
  const ManifoldCache& manifolds() const { return manifolds_; }

 private:
  SeparatingAxisCache cache_;
  PolyhedronScratch scratch_;
  std::vector<PolyhedronScratch> worker_scratch_;  // one per runner thread
  std::vector<ContactSet> slots_;                  // one per pair, kept between steps
  std::vector<AxisCacheUpdate> updates_;           // one per pair of the last CollidePairs
  bool manifold_reuse_ = kManifoldReuseDefault;
  ManifoldCache manifolds_;
  std::vector<ManifoldUpdate> manifold_updates_;   // one per pair of the last CollidePairs, when reusing
  std::vector<const CachedManifold*> kept_;        // each pair's kept manifold or null (ManifoldCache::Locate)
  // One pair of CollidePairs: its kept manifold when it may be reused, else Dispatch.
  void CollidePair(const std::vector<RigidBody>& bodies, const BodyPair& p, int i, double margin,
                   PolyhedronScratch* scratch, ContactSet* out);
  void RebuildCaches();
};

}  // namespace contactsim
