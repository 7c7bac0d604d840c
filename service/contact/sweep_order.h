// The order in which Gauss-Seidel solvers sweep a step's normal blocks
// (normal_block.h): from the highest body pair down along gravity. Solving
// the upper contacts of a stack before the lower ones lets each support see
// the load of what it carries in the same sweep; swept bottom up (the order
// of the scenes' bodies), a rocking mode of tall aligned stacks grew from
// round-off: xpbd's 8-cube stack walked 3.5 mm and ten 1 m cubes fell,
// soft's 20-cube stack leaned 9.5 mm in 10 s (docs/physics.md, "Sweep
// order"). Without gravity the detector's order is kept. A stable sort on
// positions, so the order is the same on every build.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/collision/parallel_sort.h"
#include "service/contact/normal_block.h"
#include "service/physics/world.h"

namespace contactsim {

// blocks a thread weighs, sorts as one run or moves at a time
constexpr int kSweepOrderGrain = 512;

// `points` (anything with a body index a and a lever arm ra from A's centre
// to the point) are the blocks' points; a block's height is its first
// point's. With a runner, the heights, the sort (parallel_sort.h) and the
// reordering run on its threads, with the same order as without.
template <class Point>
void OrderBlocksFromTheTop(const World& world, const std::vector<Point>& points, std::vector<NormalBlock>* blocks,
                           ParallelRunner* runner = nullptr) {
  if (world.gravity.isZero(0.0) || blocks->size() < 2) return;
  const Vec3 up = -world.gravity.normalized();
  const int n = static_cast<int>(blocks->size());
  const auto split = [runner, n](const ParallelRunner::RangeFn& body) {
    if (runner == nullptr) {
      body(0, n, 0);
    } else {
      runner->For(n, kSweepOrderGrain, body);
    }
  };
  // each block's height once (a comparison recomputing both cost 5% of a
  // soft step), then a sort of (height, index): higher first, the index
  // breaking ties, so the order is total and the sort stable
  std::vector<std::pair<double, int>> keys(n), scratch;
  split([&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      const Point& p = points[(*blocks)[k].first];
      keys[k] = {up.dot(world.bodies()[p.a].x + p.ra), k};
    }
  });
  ParallelSort(&keys, &scratch, runner, kSweepOrderGrain,
               [](const std::pair<double, int>& l, const std::pair<double, int>& r) {
                 return l.first > r.first || (l.first == r.first && l.second < r.second);
               });
  std::vector<NormalBlock> sorted(n);
  split([&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) sorted[k] = (*blocks)[keys[k].second];
  });
  blocks->swap(sorted);
}

}  // namespace contactsim
