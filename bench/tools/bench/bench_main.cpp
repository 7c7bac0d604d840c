// contactsim-bench: with --scene (or --list-methods), runs a scene file with a
// contact method and reports speed and physics (scene_bench/);
// otherwise runs the Google Benchmark micro benchmarks that every
// *_bench.cpp in this folder registers.
#include <benchmark/benchmark.h>

#include <cstring>

#include "bench/tools/scene_bench/contactsim_engine.h"
#include "bench/tools/scene_bench/scene_bench_main.h"

namespace {

bool SceneMode(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const char* a = argv[i];
    if (std::strncmp(a, "--scene", 7) == 0 || std::strcmp(a, "--list-methods") == 0 ||
        std::strcmp(a, "--help") == 0 || std::strcmp(a, "-h") == 0) {
      return true;
    }
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (SceneMode(argc, argv)) {
    contactsim::bench::RunnerInfo info;
    info.engine = "contactsim";
    info.description =
        "contactsim-bench: runs a scene with a contact method and prints ms per step, penetration, "
        "energy, displacement, rebound and memory";
    info.methods = contactsim::ContactMethodNames();
    info.threaded = true;
    info.factory = contactsim::bench::CreateContactsimEngine;
    return contactsim::bench::SceneBenchMain(argc, argv, info);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
