// Sweep and prune (sort and sweep) on one axis, incremental across steps.
//
// The boxes are kept sorted by their lower bound on the axis where the box
// centres spread most; a sweep then tests box a only against the boxes that
// start before a ends. Between steps bodies move little, so the order of the
// last step is nearly sorted and insertion sort repairs it in O(n + swaps)
// (Baraff 1992, "Dynamic simulation of non-penetrating rigid bodies", ch. 6;
// Cohen, Lin, Manocha and Ponamgi 1995, I-COLLIDE). A step costs
// O(n + swaps + k_axis), k_axis the pairs overlapping on the sweep axis; a
// fresh sort, O(n log n), happens when the body count changes, after
// Reset(), or when another axis spreads the boxes much more.
//
// The kept order is only a permutation of body indices, so a stale order
// (bodies replaced without a Reset) costs time, never correctness.
//
// In a uniform 3D scene a box overlaps O(n^(2/3)) others on one axis, so
// k_axis, not the sort, dominates for large n. The sweep therefore reads
// only contiguous arrays in sweep order (the bounds on all three axes and
// the movable flag are gathered once per call), never the caller's boxes.
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/broadphase.h"

namespace contactsim {

class SweepAndPrune : public Broadphase {
 public:
  const char* Name() const override { return "sap"; }
  void FindPairs(const std::vector<Aabb>& boxes, const std::vector<bool>& movable,
                 std::vector<BodyPair>* pairs) override;
  void Reset() override { entries_.clear(); }

  // Introspection for tests and benchmarks.
  int axis() const { return axis_; }
  bool last_rebuilt() const { return last_rebuilt_; }
  int64_t last_swaps() const { return last_swaps_; }  // insertion sort shifts of the last repair

 private:
  struct Entry {
    double min;  // m, lower bound on the sweep axis
    int index;   // body index
  };
  // what the sweep reads of a candidate, contiguous in sweep order: its
  // lower bound on the sweep axis and its bounds on the two other axes
  struct SweepBounds {
    double min, min_u, max_u, min_v, max_v;  // m
  };

  int ChooseAxis(const std::vector<Aabb>& boxes) const;
  void Rebuild(const std::vector<Aabb>& boxes);
  void Repair(const std::vector<Aabb>& boxes);
  void Gather(const std::vector<Aabb>& boxes, const std::vector<bool>& movable);
  // Appends the pairs of the boxes at sweep positions [begin, end) with the
  // boxes after them.
  void Sweep(int begin, int end, std::vector<BodyPair>* pairs) const;
  // body over [0, n) on the runner's threads, or on this one without a runner
  void Split(int n, int grain, const ParallelRunner::RangeFn& body) const;
  // `pairs` of bodies below n in (first, second) order.
  void SortPairsByBody(int n, std::vector<BodyPair>* pairs);

  std::vector<int> first_counts_;  // SortPairsByBody's scratch
  std::vector<BodyPair> sorted_;
  std::vector<std::vector<BodyPair>> worker_pairs_;  // per thread, of the sweep
  int axis_ = 0;
  std::vector<Entry> entries_;  // sorted by (min, index)
  std::vector<Entry> entry_scratch_;  // the repair's merges
  // gathered in sweep order each call
  std::vector<double> max_;     // m, upper bounds on the sweep axis
  std::vector<SweepBounds> sweep_;
  std::vector<uint8_t> movable_;
  bool last_rebuilt_ = false;
  int64_t last_swaps_ = 0;
};

}  // namespace contactsim
