// Broadphase: the pairs of bodies whose bounding boxes overlap.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/parallel_runner.h"
#include "service/physics/status.h"

namespace contactsim {

// A candidate pair of body indices with first < second.
using BodyPair = std::pair<int, int>;

class Broadphase {
 public:
  virtual ~Broadphase() = default;
  virtual const char* Name() const = 0;
  // Appends the overlapping pairs, sorted ascending, to `pairs` (cleared
  // first). Pairs of two non-dynamic bodies are skipped; `movable[i]` says
  // whether body i is dynamic.
  virtual void FindPairs(const std::vector<Aabb>& boxes, const std::vector<bool>& movable,
                         std::vector<BodyPair>* pairs) = 0;
  // Drops caches (call when bodies are added or removed).
  virtual void Reset() {}
  // Threads FindPairs may use (the detector's; null or one thread: serial).
  // The pairs are the same for any number.
  void SetRunner(ParallelRunner* runner) { runner_ = runner; }

 protected:
  ParallelRunner* runner_ = nullptr;
};

// "naive" (all pairs, O(n^2)) or "sap" (sweep and prune, O(n log n + k)).
Status CreateBroadphase(const std::string& name, std::unique_ptr<Broadphase>* out);

}  // namespace contactsim
