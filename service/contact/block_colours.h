// Colours of a step's normal blocks (normal_block.h) for a parallel
// Gauss-Seidel sweep: two blocks of one colour share no movable body, so
// they may be solved at the same time, in any order, by any thread, with
// the same result bit for bit (the graph colouring of Box2D v3 and Box3D;
// docs/architecture.md, "Threads"). Static and kinematic bodies take no
// share of an impulse and are never written, so they join no colour.
//
// Greedy in the blocks' given order (from the top down, sweep_order.h):
// each block takes the lowest colour neither of its bodies has yet. The
// sweep then runs colour by colour; the serial solver uses the same order,
// so the result does not depend on the number of threads. A block that
// finds all kMaxColours taken (a body with more contact pairs than that)
// goes to the overflow, swept serially after the colours, as does every
// block of a body marked kSerial (a heavy-on-light component, whose sweep
// order the direct solve after it depends on: soft_ratio_solve.h).
#pragma once

#include <cstdint>
#include <vector>

#include "service/contact/normal_block.h"

namespace contactsim {

// What an impulse does to a body, for the colouring.
enum class ColourRole : char {
  kFixed,     // static or kinematic: never written, joins no colour
  kColoured,  // dynamic
  kSerial,    // dynamic, and its blocks keep their order in the overflow
};

struct BlockColours {
  static constexpr int kMaxColours = 32;
  // colour c's blocks are [starts[c], starts[c + 1]) of the reordered
  // blocks; the overflow is [starts.back(), blocks.size())
  std::vector<int> starts;
  // where each run of the overflow that shares no movable body with the
  // others starts, then the blocks' count (overflow_runs.h); empty: the
  // overflow is one run
  std::vector<int> overflow_runs;
  int colours() const { return static_cast<int>(starts.size()) - 1; }
};

// Reorders `blocks` colour by colour (a stable partition of the given
// order) and returns where each colour starts. `points` are the blocks'
// points (anything with body indices a and b); `roles` has one entry per
// body.
template <class Point>
BlockColours ColourBlocks(const std::vector<Point>& points, const std::vector<ColourRole>& roles,
                          std::vector<NormalBlock>* blocks) {
  constexpr int kOverflow = BlockColours::kMaxColours;
  std::vector<uint32_t> used(roles.size(), 0u);  // per body: bit c = has a block of colour c
  std::vector<int> colour(blocks->size());
  int counts[kOverflow + 1] = {};
  for (size_t k = 0; k < blocks->size(); ++k) {
    const int a = points[(*blocks)[k].first].a, b = points[(*blocks)[k].first].b;
    const bool serial = roles[a] == ColourRole::kSerial || roles[b] == ColourRole::kSerial;
    const bool colour_a = roles[a] == ColourRole::kColoured, colour_b = roles[b] == ColourRole::kColoured;
    const uint32_t taken = serial ? ~0u : (colour_a ? used[a] : 0u) | (colour_b ? used[b] : 0u);
    int c = 0;
    while (c < kOverflow && (taken & (1u << c)) != 0u) ++c;
    if (c < kOverflow) {
      if (colour_a) used[a] |= 1u << c;
      if (colour_b) used[b] |= 1u << c;
    }
    colour[k] = c;
    ++counts[c];
  }
  int colours = 0;
  while (colours < kOverflow && counts[colours] > 0) ++colours;  // greedy: no gaps below the highest
  int offsets[kOverflow + 1];
  for (int c = 0, start = 0; c <= kOverflow; start += counts[c], ++c) offsets[c] = start;
  BlockColours out;
  out.starts.assign(offsets, offsets + colours + 1);  // offsets[colours] == the overflow's start
  std::vector<NormalBlock> sorted(blocks->size());
  for (size_t k = 0; k < blocks->size(); ++k) sorted[offsets[colour[k]]++] = (*blocks)[k];
  blocks->swap(sorted);
  return out;
}

}  // namespace contactsim
