// A sort on a ParallelRunner's threads (docs/architecture.md, "Threads"):
// runs of `run` elements sorted apart (the same runs however the range is
// split over the threads), then merged pairwise, wider and wider, each
// merge of a level on any thread. For a total order (no two elements
// equivalent) the result is what one std::sort gives, bit for bit, on any
// number of threads; callers make their order total with an index. With
// a count asked for, it also counts the inversions (the shifts an
// insertion sort of the whole range would make): within each run, and
// across two runs as they merge.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "service/collision/parallel_runner.h"

namespace contactsim {

// Sorts [first, last) by `less`, a total order: by insertion while the
// elements stand near their places (at most two moves an element), else by
// std::sort. The warm-start cache's entries come pair by pair in body order,
// out of order only within a pair, where std::sort's partitions cost n log n
// moves of large entries. A total order has one sorted result, so either
// way gives the same, bit for bit. With `shifts`, by insertion alone (in
// O(n + inversions)), adding the inversions to *shifts.
template <class It, class Less>
void SortRun(It first, It last, Less less, int64_t* shifts = nullptr) {
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
    if (shifts != nullptr) {
      *shifts += i - j;
    } else if (budget < 0) {
      std::sort(first, last, less);
      return;
    }
  }
}

// std::merge of two sorted ranges, returning the inversions between them:
// for each element taken from the second, the first's elements still left.
template <class It, class Out, class Less>
int64_t MergeCounting(It first1, It last1, It first2, It last2, Out out, Less less) {
  int64_t inversions = 0;
  while (first1 != last1 && first2 != last2) {
    if (less(*first2, *first1)) {
      inversions += last1 - first1;
      *out++ = *first2++;
    } else {
      *out++ = *first1++;
    }
  }
  out = std::copy(first1, last1, out);
  std::copy(first2, last2, out);
  return inversions;
}

// Sorts `v` by `less`, a total order; `scratch` is the merges' buffer
// (grown to v's size, kept by the caller so a warmed-up step allocates
// nothing). A null runner sorts on the caller. With `inversions`, sets it
// to v's inversions before the sort (the runs then sort by insertion).
template <class T, class Less>
void ParallelSort(std::vector<T>* v, std::vector<T>* scratch, ParallelRunner* runner, int run, Less less,
                  int64_t* inversions = nullptr) {
  const auto split = [runner](int count, int grain, const ParallelRunner::RangeFn& body) {
    if (runner == nullptr) {
      body(0, count, 0);
    } else {
      runner->For(count, grain, body);
    }
  };
  const int m = static_cast<int>(v->size());
  const auto begin = v->begin();
  std::atomic<int64_t> count{0};  // an integer sum: the same in any order
  const bool counting = inversions != nullptr;
  split(m, run, [&](int lo, int hi, int /*worker*/) {
    int64_t shifts = 0;
    for (int r = lo; r < hi; r += run) {
      SortRun(begin + r, begin + std::min(r + run, hi), less, counting ? &shifts : nullptr);
    }
    count += shifts;
  });
  if (counting) *inversions = count;
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
        // (no element outside the overlap is out of order with the other run)
        const auto out = scratch->begin() + (from - begin);
        if (counting) {
          count += MergeCounting(from, begin + mid, begin + mid, to, out, less);
        } else {
          std::merge(from, begin + mid, begin + mid, to, out, less);
        }
        std::copy(out, out + (to - from), from);
      }
    });
  }
  if (counting) *inversions = count;
}

}  // namespace contactsim
