// The soft step's points laid out in the order its passes take them.
//
// The narrowphase emits the points pair by pair, in the broadphase's order,
// while the passes sweep the manifolds colour by colour, each colour from
// the top down (sweep_order.h, block_colours.h): a colour pass over a
// world of many stacks jumps between points far apart in memory, each
// manifold's 0.5-2 KiB a fetch of its own. Copied once a step into the
// order of the manifolds, every colour pass reads the points front to back
// (BENCHMARKS.md, "Scaling: 1,000 to 10,000 bodies"). Only where the
// points live changes: each pass solves the same manifolds in the same
// order, and the warm start sums a body's impulses in contact order
// (SoftPointsOfBodies), so the results are the same bit for bit.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/soft/soft_manifold.h"

namespace contactsim {

class SoftPointOrder {
 public:
  // The points back in contact order (as PrepareSoftPoints writes them).
  void Reset() { point_of_contact_.clear(); }
  // Moves `points` (in contact order) into the order of `manifolds`, each
  // manifold's first rewritten and its K^-1 taken from the copies while
  // they are in the cache (InvertSoftManifold: a pass of its own fetched
  // every point again), on the runner's threads.
  void Apply(ParallelRunner& runner, std::vector<SoftManifold>* manifolds, std::vector<SoftPoint>* points);
  // where contact k's point is
  int PointOf(int contact) const { return point_of_contact_.empty() ? contact : point_of_contact_[contact]; }
  // null while the points are in contact order
  const std::vector<int>* PointsOfContacts() const {
    return point_of_contact_.empty() ? nullptr : &point_of_contact_;
  }

 private:
  std::vector<int> point_of_contact_;
  std::vector<SoftPoint> scratch_;  // the other buffer, swapped with the points each step
  std::vector<int> starts_;
};

}  // namespace contactsim
