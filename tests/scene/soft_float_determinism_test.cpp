// The soft step's float path (precision=float, service/contact/soft/wide/)
// on the standard scenes without joints, which it steps: it must end each
// on its pinned hash whatever the thread count and whatever the SIMD width
// (4 or 8 lanes a bundle), since every lane is one manifold's own
// arithmetic and the colours fix the order (soft_wide_solver.h). Where the
// processor has no AVX, float_lanes=8 runs 4 lanes, and the hash is the
// same. A change meant to change the float path's physics changes these
// pins: run `scene_tests --gtest_filter='SoftFloat*'` and copy the hashes.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cinttypes>
#include <cstdio>

#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace {

struct PinnedFloatRun {
  const char* scene;
  int steps;
  uint64_t hash;
};
// the pyramid rests from the first step; the pile's and the rain's lowest
// layer lands after ~68 steps, and the rest keeps landing on it
constexpr PinnedFloatRun kFloatRuns[] = {
    {"box_pyramid.pbtxt", 48, 0xbb8811f80bcd0682ull},
    {"sphere_pile.pbtxt", 120, 0x099d1487e45a5127ull},
    {"box_rain.pbtxt", 120, 0x6c3eef658bf0bbbeull},
};

// Verifies the pinned hash at 4 and 8 lanes on 1, 2 and 4 threads.
TEST(SoftFloatDeterminismTest, EndsEachSceneOnItsPinAtEveryWidthAndThreadCount) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const PinnedFloatRun& r : kFloatRuns) {
    for (const char* lanes : {"4", "8"}) {
      for (const int threads : {1, 2, 4}) {
        const testing_util::SceneRun run{r.scene, "soft", {{"precision", "float"}, {"float_lanes", lanes}}, r.steps,
                                         threads};
        const uint64_t hash = testing_util::RunSceneHash(run);
        std::printf("%-18s lanes %s threads %d %016" PRIx64 "\n", r.scene, lanes, threads, hash);
        EXPECT_EQ(hash, r.hash) << r.scene << " at " << lanes << " lanes on " << threads << " threads: got 0x"
                                << std::hex << hash << ", pinned 0x" << r.hash;
      }
    }
  }
}

// Verifies that precision=float takes the float path: the pyramid ends
// elsewhere than under the double path.
TEST(SoftFloatDeterminismTest, FloatPathAnswersInItsOwnPrecision) {
  const testing_util::SceneRun single{"box_pyramid.pbtxt", "soft", {{"precision", "float"}}, 12, 1};
  const testing_util::SceneRun twice{"box_pyramid.pbtxt", "soft", {{"precision", "double"}}, 12, 1};
  EXPECT_NE(testing_util::RunSceneHash(single), testing_util::RunSceneHash(twice));
}

// Verifies that a world the float path hands to the double path (here
// every point heavy-on-light: direct_mass_ratio 1) steps bit for bit as
// under precision=double, though the float path's preparation leaves the
// rows and K^-1 to its prepare kernel until it knows the path.
TEST(SoftFloatDeterminismTest, HeavyOnLightWorldStepsAsUnderTheDoublePath) {
  const testing_util::SceneRun single{
      "box_pyramid.pbtxt", "soft", {{"precision", "float"}, {"direct_mass_ratio", "1"}}, 12, 1};
  const testing_util::SceneRun twice{
      "box_pyramid.pbtxt", "soft", {{"precision", "double"}, {"direct_mass_ratio", "1"}}, 12, 1};
  EXPECT_EQ(testing_util::RunSceneHash(single), testing_util::RunSceneHash(twice));
}

}  // namespace
}  // namespace contactsim
