// The same run on any build (docs/snapshots.md, "Determinism across
// builds"): every registered contact method runs the determinism scene
// (config/scenes/determinism.pbtxt: boxes and spheres in a stack, a slide
// and a bounce, a pendulum and a hinge with limits) for the scene's steps
// and must end on the world hash pinned here. The same pins hold for the
// g++ RelWithDebInfo build (`make test`), the Debug -O1 sanitizer build
// (`make test-asan`) and the clang libFuzzer build (`make fuzz-ci`); CI
// runs all three, so a change that makes a method's result depend on the
// compiler, the optimisation level or uninitialised memory fails one. A change meant to change the
// physics changes the pins: run `scene_tests --gtest_filter='*Determinism*'`
// and copy the printed hashes.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/scene/scene_spec.h"
#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace {

// A method's configurations and the hash each must end on. Every method
// runs with its defaults; lcp also with Lemke's method, penalty also with
// the Hunt-Crossley law (whose d^1.5 is portable_math.h's pow).
struct Pinned {
  std::string method;
  ParamMap params;
  uint64_t hash;
};

const std::vector<Pinned>& PinnedRuns() {
  static const std::vector<Pinned> pinned = {
      {"impulse", {}, 0x0c9820223c4c5344ull},
      {"penalty", {}, 0xe6b488b7ca96cac1ull},
      {"penalty", {{"model", "hunt_crossley"}}, 0x9ca96564088018feull},
      {"xpbd", {}, 0x7b2388ec667ed6f5ull},
      {"lcp", {{"solver", "pgs"}}, 0xdda5c5523890dc93ull},
      {"lcp", {{"solver", "lemke"}}, 0x8c604ee582352f10ull},
      {"barrier", {}, 0x88fc6486c49e595bull},
      {"soft", {}, 0x31d6f20698c91142ull},
  };
  return pinned;
}

using testing_util::Describe;

// The world hash at the end of the determinism scene under one configuration.
uint64_t RunScene(const std::string& method_name, const ParamMap& params) {
  return testing_util::RunSceneHash({"determinism.pbtxt", method_name, params});
}

class DeterminismTest : public ::testing::TestWithParam<std::string> {};

// Verifies that each configuration of the method ends the scene on its
// pinned hash, bit for bit, whatever the compiler and optimisation level.
TEST_P(DeterminismTest, MethodEndsTheSceneOnItsPinnedHash) {
  int runs = 0;
  for (const Pinned& p : PinnedRuns()) {
    if (p.method != GetParam()) continue;
    ++runs;
    const uint64_t hash = RunScene(p.method, p.params);
    std::printf("%-24s %016" PRIx64 "\n", Describe(p.method, p.params).c_str(), hash);
    EXPECT_EQ(hash, p.hash) << Describe(p.method, p.params) << ": got 0x" << std::hex << hash << ", pinned 0x"
                            << p.hash;
  }
  EXPECT_GT(runs, 0) << "no pinned hash for the registered method " << GetParam()
                     << ": add its hash to PinnedRuns()";
}

// The methods come from the registry, so a new method fails until its
// hash is pinned.
INSTANTIATE_TEST_SUITE_P(EveryMethod, DeterminismTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace contactsim
