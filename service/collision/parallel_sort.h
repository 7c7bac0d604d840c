// A sort on a ParallelRunner's threads (docs/architecture.md, "Threads"):
// runs of `run` elements sorted apart (the same runs however the range is
// split over the threads), then merged pairwise, wider and wider, each
// merge of a level on any thread. For a total order (no two elements
// equivalent) the result is what one std::sort gives, bit for bit, on any
// number of threads; callers make their order total with an index.
#pragma once

#include <algorithm>
#include <vector>

#include "service/collision/parallel_runner.h"

namespace contactsim {

// Sorts `v` by `less`, a total order; `scratch` is the merges' buffer
// (grown to v's size, kept by the caller so a warmed-up step allocates
// nothing). A null runner sorts on the caller.
template <class T, class Less>
void ParallelSort(std::vector<T>* v, std::vector<T>* scratch, ParallelRunner* runner, int run, Less less) {
  const auto split = [runner](int count, int grain, const ParallelRunner::RangeFn& body) {
    if (runner == nullptr) {
      body(0, count, 0);
    } else {
      runner->For(count, grain, body);
    }
  };
  const int m = static_cast<int>(v->size());
  const auto begin = v->begin();
  split(m, run, [&](int lo, int hi, int /*worker*/) {
    for (int r = lo; r < hi; r += run) std::sort(begin + r, begin + std::min(r + run, hi), less);
  });
  if (m <= run) return;
  if (scratch->size() < v->size()) scratch->resize(v->size());
  for (int width = run; width < m; width *= 2) {
    const int merges = (m + 2 * width - 1) / (2 * width);
    split(merges, 1, [&](int first, int last, int /*worker*/) {
      for (int i = first; i < last; ++i) {
        const int lo = 2 * i * width, mid = std::min(lo + width, m), hi = std::min(lo + 2 * width, m);
        // runs already in order (neighbours that do not overlap) need no merge
        if (mid == hi || !less(begin[mid], begin[mid - 1])) continue;
        std::merge(begin + lo, begin + mid, begin + mid, begin + hi, scratch->begin() + lo, less);
        std::copy(scratch->begin() + lo, scratch->begin() + hi, begin + lo);
      }
    });
  }
}

}  // namespace contactsim
