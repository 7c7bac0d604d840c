// Tests of ParallelRunner: the thread-count check, and that a loop covers
// its range exactly once with worker slots in range, serially or not.
#include "service/collision/parallel_runner.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <atomic>
#include <vector>

namespace contactsim {
namespace {

// Verifies that counts from 1 to kMaxThreads pass and that others are
// refused with a message naming the value.
TEST(ParallelRunnerTest, ThreadCountCheckNamesTheValue) {
  EXPECT_TRUE(CheckThreadCount(1).ok());
  EXPECT_TRUE(CheckThreadCount(kMaxThreads).ok());
  for (const int64_t bad : {int64_t{0}, int64_t{-3}, int64_t{kMaxThreads + 1}, int64_t{1} << 40}) {
    const Status st = CheckThreadCount(bad);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << bad;
    EXPECT_EQ(st.message(), "threads must be between 1 and 256, got " + std::to_string(bad));
  }
  EXPECT_GE(DefaultThreadCount(), 1);
  EXPECT_LE(DefaultThreadCount(), kMaxThreads);
}

// Verifies that one thread runs the whole range as one call on the caller.
TEST(ParallelRunnerTest, OneThreadIsOneSerialCall) {
  ParallelRunner runner(1);
  int calls = 0;
  runner.For(1000, 1, [&](int begin, int end, int worker) {
    ++calls;
    EXPECT_EQ(begin, 0);
    EXPECT_EQ(end, 1000);
    EXPECT_EQ(worker, 0);
  });
  EXPECT_EQ(calls, 1);
}

// Verifies that with several threads every index is visited exactly once,
// in ranges of at least the grain (but the last), by workers below the
// thread count, however often it runs.
TEST(ParallelRunnerTest, EveryIndexOnceWithWorkersInRange) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const int threads : {2, 3, 4}) {
    ParallelRunner runner(threads);
    for (int round = 0; round < 20; ++round) {
      constexpr int kN = 5000;
      constexpr int kGrain = 7;
      std::vector<std::atomic<int>> visits(kN);
      std::atomic<int> bad_workers{0};
      runner.For(kN, kGrain, [&](int begin, int end, int worker) {
        if (worker < 0 || worker >= threads) ++bad_workers;
        for (int i = begin; i < end; ++i) ++visits[i];
      });
      EXPECT_EQ(bad_workers.load(), 0);
      for (int i = 0; i < kN; ++i) ASSERT_EQ(visits[i].load(), 1) << "index " << i << ", " << threads << " threads";
    }
  }
}

// Verifies that a range no longer than the grain runs on the caller.
TEST(ParallelRunnerTest, ShortRangesRunSerially) {
  ParallelRunner runner(4);
  int calls = 0;
  runner.For(16, 16, [&](int begin, int end, int worker) {
    ++calls;
    EXPECT_EQ(begin, 0);
    EXPECT_EQ(end, 16);
    EXPECT_EQ(worker, 0);
  });
  runner.For(0, 16, [&](int, int, int) { ++calls; });
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace contactsim
