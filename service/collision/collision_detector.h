// The collision pipeline of one step: bounding boxes, broadphase, narrowphase.
// The bounding boxes and the narrowphase run on the detector's own threads
// (parallel_runner.h; docs/architecture.md, "Threads") with the same result,
// bit for bit, for any number of them; so does the broadphase's sweep.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "service/collision/broadphase.h"
#include "service/collision/contact.h"
#include "service/collision/narrowphase.h"
#include "service/collision/parallel_runner.h"
#include "service/physics/world.h"

namespace contactsim {

struct CollisionStats {
  int candidate_pairs = 0;  // from the broadphase, last Detect
  int contacts = 0;         // last Detect
  int64_t detections = 0;   // Detect calls since construction
};

class CollisionDetector {
 public:
  CollisionDetector();  // sweep and prune, one thread
  Status SetBroadphase(const std::string& name);
  const char* broadphase_name() const { return broadphase_->Name(); }
  // Threads for the per-body and per-pair loops (the `threads` setting):
  // InvalidArgument naming the value unless CheckThreadCount accepts it,
  // and then nothing changes. 1 is the serial code path.
  Status SetThreads(int threads);
  int threads() const { return runner_->threads(); }
  // Manifold reuse for touching polyhedron pairs (the `manifold_reuse`
  // setting, manifold_cache.h; docs/physics.md, "Collision").
  void SetManifoldReuse(bool on) { narrowphase_.SetManifoldReuse(on); }
  bool manifold_reuse() const { return narrowphase_.manifold_reuse(); }
  // The kept manifolds are the detector's only state that changes results
  // (the separating-axis cache and the broadphase's order change only
  // speed): a snapshot saves them and a restore puts them back
  // (service/scene/snapshot_manifolds.h).
  const ManifoldCache& manifolds() const { return narrowphase_.manifolds(); }
  void RestoreManifolds(std::vector<CachedManifold> entries) { narrowphase_.RestoreManifolds(std::move(entries)); }
  // The world's threads, for the contact methods' solvers too.
  ParallelRunner& runner() const { return *runner_; }

  // Contacts of the world at its current poses with depth > -margin (m).
  // Boxes are swept by v * sweep_dt so that pairs about to meet are found.
  // Only the pairs ShouldCollide accepts (collision_filter.h) reach the
  // narrowphase: their filters, and the two bodies of a joint without
  // collide_connected never touch (as MuJoCo excludes a body and its
  // parent, and Bullet's disableCollisionsBetweenLinkedBodies): the joint
  // holds them, and the links of a chain touch at their joints. The test
  // runs once on the broadphase's pairs, so every broadphase agrees.
  void Detect(const World& world, double margin, double sweep_dt, ContactSet* contacts);
  // The candidate pairs of the last Detect (body indices).
  const std::vector<BodyPair>& pairs() const { return pairs_; }
  const CollisionStats& stats() const { return stats_; }
  void Reset() {
    broadphase_->Reset();
    narrowphase_.Reset();
  }
  // Separating-axis cache counters (Baraff): hits skipped the full test.
  const Narrowphase& narrowphase() const { return narrowphase_; }

 private:
  std::unique_ptr<Broadphase> broadphase_;
  std::unique_ptr<ParallelRunner> runner_;
  Narrowphase narrowphase_;
  std::vector<Aabb> boxes_;
  std::vector<bool> movable_;
  // per body index: the hull vertices that bounded its last box, where the
  // next box's descents start (ComputeAabb); any start gives the same box
  std::vector<AabbSupport> supports_;
  void ComputeBoxes(const World& world, double margin, double sweep_dt);
  void DropFilteredPairs(const World& world);

  std::vector<BodyPair> pairs_;
  CollisionStats stats_;
};

}  // namespace contactsim
