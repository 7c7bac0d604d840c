// Tests of ParallelSort: on 1, 2 and 4 threads, with or without a runner
// and for any run length, a total order comes out as one std::sort's, bit
// for bit, including runs already in order and sizes that are not a
// multiple of the run; the inversions it counts are an insertion sort's
// shifts.
#include "service/collision/parallel_sort.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <utility>
#include <vector>

namespace contactsim {
namespace {

// (value, index) higher value first, the index breaking ties: the order
// sweep_order.h sorts its blocks by
bool HigherFirst(const std::pair<double, int>& l, const std::pair<double, int>& r) {
  return l.first > r.first || (l.first == r.first && l.second < r.second);
}

std::vector<std::pair<double, int>> RandomKeys(int n, int distinct, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, distinct - 1);
  std::vector<std::pair<double, int>> keys(n);
  for (int k = 0; k < n; ++k) keys[k] = {0.25 * value(rng), k};
  return keys;
}

// Verifies that sizes around the run length and across several merge
// levels, with many equal values (ties broken by the index), sort to what
// std::sort gives whatever the thread count and the run.
TEST(ParallelSortTest, MatchesOneStdSortOnAnyThreadCount) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const int n : {0, 1, 7, 64, 65, 500, 1024, 3001}) {
    for (const int distinct : {3, 1000000}) {
      const std::vector<std::pair<double, int>> keys = RandomKeys(n, distinct, 7u + n);
      std::vector<std::pair<double, int>> expected = keys;
      std::sort(expected.begin(), expected.end(), HigherFirst);
      for (const int run : {1, 16, 64, 1000}) {
        std::vector<std::pair<double, int>> serial = keys, scratch;
        ParallelSort(&serial, &scratch, nullptr, run, HigherFirst);
        EXPECT_EQ(serial, expected) << "n " << n << " run " << run << " without a runner";
        for (const int threads : {1, 2, 4}) {
          ParallelRunner runner(threads);
          std::vector<std::pair<double, int>> sorted = keys;
          ParallelSort(&sorted, &scratch, &runner, run, HigherFirst);
          EXPECT_EQ(sorted, expected) << "n " << n << " run " << run << " threads " << threads;
        }
      }
    }
  }
}

// Verifies that input already in order (the warm-start cache's contacts
// come pair by pair) and input in reverse both come out sorted.
TEST(ParallelSortTest, SortedAndReversedInputs) {
  ParallelRunner runner(2);
  std::vector<int> up(5000), down(5000), scratch;
  for (int k = 0; k < 5000; ++k) up[k] = k, down[k] = 4999 - k;
  ParallelSort(&up, &scratch, &runner, 256, std::less<int>());
  ParallelSort(&down, &scratch, &runner, 256, std::less<int>());
  EXPECT_TRUE(std::is_sorted(up.begin(), up.end()));
  EXPECT_EQ(down, up);
}

// Verifies that input out of order only within small groups (the
// warm-start cache's entries, out of order within a pair), with the groups
// split by the runs' ends so that neighbouring runs overlap by a few
// elements, sorts to what std::sort gives.
TEST(ParallelSortTest, InputOutOfOrderWithinGroups) {
  std::vector<int> keys(3001);
  for (int k = 0; k < 3001; ++k) keys[k] = k - 2 * (k % 3) + 2;  // each group of three reversed
  std::vector<int> expected = keys;
  std::sort(expected.begin(), expected.end());
  for (const int run : {16, 64, 1000}) {
    for (const int threads : {1, 2}) {
      ParallelRunner runner(threads);
      std::vector<int> sorted = keys, scratch;
      ParallelSort(&sorted, &scratch, &runner, run, std::less<int>());
      EXPECT_EQ(sorted, expected) << "run " << run << " threads " << threads;
    }
  }
}

// Verifies that the inversions counted (sweep_and_prune.cpp's repair
// reports them as its insertion sort's shifts) are the pairs out of order,
// counted one by one, on any thread count and run, for nearly sorted and
// shuffled input alike, and that the sort still matches std::sort.
TEST(ParallelSortTest, CountsTheInversions) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  std::mt19937 rng(3);
  const auto less = [](const std::pair<double, int>& l, const std::pair<double, int>& r) { return HigherFirst(r, l); };
  for (const int n : {0, 1, 65, 1000, 2049}) {
    for (const int spread : {3, 1000000}) {
      std::vector<std::pair<double, int>> keys(n);
      std::uniform_int_distribution<int> jitter(0, spread);
      for (int k = 0; k < n; ++k) keys[k] = {0.5 * (k + jitter(rng)), k};  // near its place for spread 3
      int64_t expected_count = 0;
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) expected_count += less(keys[j], keys[i]) ? 1 : 0;
      }
      std::vector<std::pair<double, int>> expected = keys;
      std::sort(expected.begin(), expected.end(), less);
      for (const int run : {16, 512}) {
        for (const int threads : {1, 2, 4}) {
          ParallelRunner runner(threads);
          std::vector<std::pair<double, int>> sorted = keys, scratch;
          int64_t count = -1;
          ParallelSort(&sorted, &scratch, &runner, run, less, &count);
          EXPECT_EQ(sorted, expected) << "n " << n << " run " << run << " threads " << threads;
          EXPECT_EQ(count, expected_count) << "n " << n << " run " << run << " threads " << threads;
        }
      }
    }
  }
}

}  // namespace
}  // namespace contactsim
