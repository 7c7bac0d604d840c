// The overflow of a colouring (block_colours.h: the blocks swept in their
// given order after the colours) split into runs that share no movable
// body: the connected components of its blocks through their dynamic
// bodies. A block changes only its own bodies, and static and kinematic
// ones not at all, so the blocks of one run never read what another run's
// write: the runs may be swept at the same time, each in its given order,
// with the result of the one serial sweep bit for bit (the split of a
// Gauss-Seidel sweep into independent islands, as Box2D's and Bullet's
// islands; docs/architecture.md, "Threads").
#pragma once

#include <vector>

#include "service/contact/block_colours.h"
#include "service/contact/normal_block.h"
#include "service/contact/union_find.h"

namespace contactsim {

// Reorders the overflow of `blocks` run by run (the runs in the order of
// their first block, each run's blocks in their given order) and sets
// colours->overflow_runs to where each run starts, ending with
// blocks->size(); left empty when the overflow is one run or none.
// `points` are the blocks' points (anything with body indices a and b),
// `roles` has one entry per body.
template <class Point>
void SplitOverflow(const std::vector<Point>& points, const std::vector<ColourRole>& roles, BlockColours* colours,
                   std::vector<NormalBlock>* blocks) {
  colours->overflow_runs.clear();
  const int first = colours->starts.back();
  const int end = static_cast<int>(blocks->size());
  if (end - first < 2) return;
  const auto movable = [&roles](int body) { return roles[body] != ColourRole::kFixed; };
  UnionFind bodies(static_cast<int>(roles.size()));
  for (int k = first; k < end; ++k) {
    const int a = points[(*blocks)[k].first].a, b = points[(*blocks)[k].first].b;
    if (movable(a) && movable(b)) bodies.Join(a, b);
  }
  // each block's run, numbered by first appearance; a block on no movable
  // body writes nothing and is a run of its own
  std::vector<int> run_of_root(roles.size(), -1);
  std::vector<int> run(end - first);
  std::vector<int> counts;
  for (int k = first; k < end; ++k) {
    const int a = points[(*blocks)[k].first].a, b = points[(*blocks)[k].first].b;
    const int body = movable(a) ? a : (movable(b) ? b : -1);
    int* slot = body >= 0 ? &run_of_root[bodies.Root(body)] : nullptr;
    if (slot == nullptr || *slot < 0) {
      counts.push_back(0);
      if (slot != nullptr) *slot = static_cast<int>(counts.size()) - 1;
    }
    run[k - first] = slot != nullptr ? *slot : static_cast<int>(counts.size()) - 1;
    ++counts[run[k - first]];
  }
  if (counts.size() < 2) return;
  // a stable counting sort of the overflow by run
  std::vector<int>& starts = colours->overflow_runs;
  starts.assign(counts.size() + 1, first);
  for (size_t r = 0; r < counts.size(); ++r) starts[r + 1] = starts[r] + counts[r];
  std::vector<int> next(starts.begin(), starts.end() - 1);
  std::vector<NormalBlock> sorted(end - first);
  for (int k = first; k < end; ++k) sorted[next[run[k - first]]++ - first] = (*blocks)[k];
  std::copy(sorted.begin(), sorted.end(), blocks->begin() + first);
}

}  // namespace contactsim
