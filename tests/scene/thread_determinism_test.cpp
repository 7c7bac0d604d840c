// The same state whatever the thread count (docs/architecture.md,
// "Threads"): every registered contact method runs the standard scenes for
// a short while with the collision detector on 1, 2 and 4 threads and must
// end on the same world hash. 1 thread is the serial code path, whose
// results the pinned hashes of determinism_test.cpp hold.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cinttypes>
#include <cstdio>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace {

// Steps per scene, as few as keep every method fast while the detector
// reports contacts: the pyramid rests on the ground from the first step;
// the lowest layer of the pile and of the rain reaches the ground after
// 0.4 m of free fall, ~68 steps of 1/240 s.
struct ShortRun {
  const char* scene;
  int steps;
};
constexpr ShortRun kRuns[] = {{"box_pyramid.pbtxt", 12}, {"sphere_pile.pbtxt", 76}, {"box_rain.pbtxt", 76}};

class ThreadDeterminismTest : public ::testing::TestWithParam<std::string> {};

// Verifies that 2 and 4 threads end each standard scene on the 1-thread hash.
TEST_P(ThreadDeterminismTest, HashDoesNotDependOnThreads) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  // a method that finds its own pairs (barrier: pair_search.h) never asks
  // the detector, so its threads cannot matter; one step tells
  if (testing_util::RunSceneOnce({kRuns[0].scene, GetParam(), {}, 1, 1}).detections == 0) {
    GTEST_SKIP() << GetParam() << " does not call the collision detector";
  }
  for (const ShortRun& r : kRuns) {
    testing_util::SceneRun run{r.scene, GetParam(), {}, r.steps, 1};
    const testing_util::SceneRunResult serial = testing_util::RunSceneOnce(run);
    std::printf("%-10s %-18s %016" PRIx64 "\n", GetParam().c_str(), r.scene, serial.hash);
    for (const int threads : {2, 4}) {
      run.threads = threads;
      const uint64_t hash = testing_util::RunSceneHash(run);
      EXPECT_EQ(hash, serial.hash) << GetParam() << " on " << r.scene << " with " << threads << " threads: 0x"
                                   << std::hex << hash << ", 1 thread 0x" << serial.hash;
    }
  }
}

// Verifies the same with manifold reuse off (manifold_cache.h; the test
// above runs the default, on, whose kept manifolds are state carried from
// step to step): on the two box scenes, where touching box pairs keep theirs.
TEST_P(ThreadDeterminismTest, HashWithoutManifoldReuseDoesNotDependOnThreads) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  if (testing_util::RunSceneOnce({kRuns[0].scene, GetParam(), {}, 1, 1}).detections == 0) {
    GTEST_SKIP() << GetParam() << " does not call the collision detector";
  }
  // soft's float path too, whose rows are built from the same contacts
  std::vector<ParamMap> variants = {{}};
  if (GetParam() == "soft") variants.push_back({{"precision", "float"}});
  for (const ParamMap& params : variants) {
    for (const ShortRun& r : {kRuns[0], kRuns[2]}) {
      testing_util::SceneRun run{r.scene, GetParam(), params, r.steps, 1, false};
      const uint64_t serial = testing_util::RunSceneHash(run);
      for (const int threads : {2, 4}) {
        run.threads = threads;
        const uint64_t hash = testing_util::RunSceneHash(run);
        EXPECT_EQ(hash, serial) << testing_util::Describe(GetParam(), params) << " on " << r.scene << " with "
                                << threads << " threads: 0x" << std::hex << hash << ", 1 thread 0x" << serial;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, ThreadDeterminismTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace contactsim
