// Tests of ParallelRunner: the thread-count check, that a loop covers its
// range exactly once with worker slots in range, serially or not, and that
// Stages keeps its barriers whoever runs what.
#include "service/collision/parallel_runner.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <atomic>
#include <limits>
#include <thread>
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

// Stages of various sizes and grains (empty, shorter than the grain, a
// grain of INT_MAX for a serial stage, a grain of 1), each recording its
// visits and checking that the stage before it had finished.
struct StagePlan {
  std::vector<int> sizes = {1000, 0, 3, 1, 777, 64, 5000, 2};
  std::vector<int> grains = {7, 5, 100, std::numeric_limits<int>::max(), 1, 64, 333, 1};
  std::vector<std::vector<std::atomic<int>>> visits;
  std::vector<std::atomic<int>> finished;
  std::atomic<int> early{0};  // indices that started before the previous stage had finished
  std::vector<ParallelRunner::StageFn> fns;

  StagePlan() : visits(sizes.size()), finished(sizes.size()) {
    for (size_t s = 0; s < sizes.size(); ++s) {
      visits[s] = std::vector<std::atomic<int>>(sizes[s]);
      fns.push_back([this, s](int begin, int end) {
        if (s > 0 && finished[s - 1].load() != sizes[s - 1]) ++early;
        for (int i = begin; i < end; ++i) ++visits[s][i - 100];
        finished[s] += end - begin;
      });
    }
  }
  std::vector<ParallelRunner::Stage> Stages() const {
    std::vector<ParallelRunner::Stage> stages;
    for (size_t s = 0; s < sizes.size(); ++s) stages.push_back({&fns[s], 100, 100 + sizes[s], grains[s]});
    return stages;
  }
  void Check(int threads) const {
    EXPECT_EQ(early.load(), 0) << threads << " threads";
    for (size_t s = 0; s < sizes.size(); ++s) {
      for (int i = 0; i < sizes[s]; ++i) ASSERT_EQ(visits[s][i].load(), 1) << "stage " << s << " index " << i;
    }
  }
};

// Verifies that every index of every stage runs exactly once, offset by the
// stage's begin, and never before the previous stage is done, for 1 to 4
// threads, many times over.
TEST(ParallelRunnerTest, StagesRunEveryIndexOnceAfterThePreviousStage) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const int threads : {1, 2, 3, 4}) {
    ParallelRunner runner(threads);
    for (int round = 0; round < 20; ++round) {
      StagePlan plan;
      runner.Stages(plan.Stages());
      plan.Check(threads);
    }
  }
}

// Verifies that a chain of stages, each reading what the previous one wrote
// at other indices, ends exactly as the serial run does, and that an empty
// list returns at once.
TEST(ParallelRunnerTest, StagesMatchTheSerialResult) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  const auto run = [](int threads) {
    ParallelRunner runner(threads);
    runner.Stages({});
    constexpr int kN = 2000;
    std::vector<double> a(kN, 1.0), b(kN, 0.0);
    const ParallelRunner::StageFn spread = [&](int i, int j) {
      for (int k = i; k < j; ++k) b[k] = 0.5 * (a[(k + 1) % kN] + a[(k + kN - 7) % kN]) + k;
    };
    const ParallelRunner::StageFn gather = [&](int i, int j) {
      for (int k = i; k < j; ++k) a[k] = b[(k * 13) % kN] * 1e-3;
    };
    std::vector<ParallelRunner::Stage> stages;
    for (int pass = 0; pass < 50; ++pass) {
      stages.push_back({&spread, 0, kN, 37});
      stages.push_back({&gather, 0, kN, 101});
    }
    runner.Stages(stages);
    return a;
  };
  const std::vector<double> serial = run(1);
  for (const int threads : {2, 4}) EXPECT_EQ(run(threads), serial) << threads << " threads";
}

// Verifies that two worlds' runners, stepping at the same time on more
// threads than oneTBB will give them together, both finish: no thread
// waits for a particular other one, so a runner whose helper never starts
// runs every stage on its caller.
TEST(ParallelRunnerTest, StagesFinishWhenHelpersNeverCome) {
  oneapi::tbb::global_control one_worker(oneapi::tbb::global_control::max_allowed_parallelism, 2);
  std::vector<std::thread> worlds;
  std::atomic<int> failures{0};
  for (int w = 0; w < 3; ++w) {
    worlds.emplace_back([&failures] {
      ParallelRunner runner(4);
      for (int round = 0; round < 20; ++round) {
        StagePlan plan;
        runner.Stages(plan.Stages());
        if (plan.early.load() != 0) ++failures;
        for (size_t s = 0; s < plan.sizes.size(); ++s) {
          for (int i = 0; i < plan.sizes[s]; ++i) failures += plan.visits[s][i].load() != 1;
        }
      }
    });
  }
  for (std::thread& t : worlds) t.join();
  EXPECT_EQ(failures.load(), 0);
}

}  // namespace
}  // namespace contactsim
