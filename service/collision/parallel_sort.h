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

// Sorts [first, last) by `less`, a total order: by insertion while the
// elements stand near their places (at most two moves an element), else by
// std::sort. The warm-start cache's entries come pair by pair in body order,
// out of order only within a pair, where std::sort's partitions cost n log n
// moves of large entries. A total order has one sorted result, so either
// way gives the same, bit for bit.
template <class It, class Less>
void SortRun(It first, It last, Less less) {
  if (last - first < 2) return;
  auto budget = 2 * (last - first);
  for (It i = first + 1; i != last; ++i) {
    if (!less(*i, *(i - 1))) continue;
    auto value = std::move(*i);
    It j = i;
    do {
      *j = std::move(*(j - 1));
      --j;
      --budget;
    } while (j != first && less(value, *(j - 1)));
    *j = std::move(value);
    if (budget < 0) {
      std::sort(first, last, less);
      return;
    }
  }
}

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
    for (int r = lo; r < hi; r += run) SortRun(begin + r, begin + std::min(r + run, hi), less);
  });
  if (m <= run) return;
  if (scratch->size() < v->size()) scratch->resize(v->size());
  for (int width = run; width < m; width *= 2) {
    const int merges = (m + 2 * width - 1) / (2 * width);
    split(merges, 1, [&](int first, int last, int /*worker*/) {
      for (int i = first; i < last; ++i) {
        const int lo = 2 * i * width, mid = std::min(lo + width, m), hi = std::min(lo + 2 * width, m);
        // runs already in order (neighbours that do not overlap) need no
        // merge, and of overlapping ones only the overlap: the left run's
        // elements after the right's first and the right's before the
        // left's last (a pair's warm-start entries split by a run's end)
        if (mid == hi || !less(begin[mid], begin[mid - 1])) continue;
        const auto from = std::upper_bound(begin + lo, begin + mid, begin[mid], less);
        const auto to = std::lower_bound(begin + mid, begin + hi, begin[mid - 1], less);
        const auto out = scratch->begin() + (from - begin);
        std::merge(from, begin + mid, begin + mid, to, out, less);
        std::copy(out, out + (to - from), from);
      }
    });
  }
}

}  // namespace contactsim
