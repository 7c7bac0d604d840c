// Broadphase scaling: naive (all pairs, O(n^2)) against sweep and prune
// (O(n log n + k) from scratch, near O(n + k) when repaired incrementally).
//
// Scenes: n boxes of side 0.1..1 m, uniform in a cube sized so that a box
// overlaps about two others (about n pairs in all), one in five static.
//   Random:   each call gets the next of kRandomScenes independent scenes,
//             so there is no coherence (and the branch predictor cannot
//             learn one scene's comparisons, which made a single repeated
//             scene look ~1.7x faster); sap is Reset() every call.
//   Coherent: every call first moves each dynamic box by 1 cm (its own
//             constant velocity, bouncing off the walls), as a 1 ms step at
//             10 m/s would; sap repairs last call's order. The move costs
//             ~3 ns per box and is included.
//   SapCoherentRebuild: the coherent scene with a Reset() every call, to
//             show what the incremental repair saves.
// Run (see BENCHMARKS.md, "Broadphase scaling"):
//   build/bin/contactsim-bench --benchmark_filter=Broadphase
//       --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "service/collision/naive_broadphase.h"
#include "service/collision/sweep_and_prune.h"

namespace contactsim {
namespace {

constexpr double kDensity = 2.0;   // expected overlaps per box
constexpr double kMoveStep = 0.01; // m per call in the coherent variant
constexpr int kLargeN = 50000;     // naive takes seconds per call here
constexpr int kLargeNIterations = 3;
constexpr int kRandomScenes = 4;

struct BenchScene {
  std::vector<Aabb> boxes;
  std::vector<bool> movable;
  std::vector<Vec3> velocity;  // m per call
  double side = 0.0;           // m, the cube the boxes live in

  BenchScene(int n, unsigned seed) {
    // P(overlap) = (2 s / side)^3 with mean side s = 0.55 m; = kDensity / n
    side = 2.0 * 0.55 * std::cbrt(n / kDensity);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pos(0.0, side), ext(0.05, 0.5), dir(-1.0, 1.0);
    std::bernoulli_distribution is_static(0.2);
    for (int i = 0; i < n; ++i) {
      const Vec3 c{pos(rng), pos(rng), pos(rng)}, h{ext(rng), ext(rng), ext(rng)};
      boxes.push_back({c - h, c + h});
      movable.push_back(!is_static(rng));
      velocity.push_back(Vec3{dir(rng), dir(rng), dir(rng)}.normalized() * kMoveStep);
    }
  }

  void Move() {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (!movable[i]) continue;
      for (int k = 0; k < 3; ++k) {
        if ((boxes[i].min[k] < 0.0 && velocity[i][k] < 0.0) || (boxes[i].max[k] > side && velocity[i][k] > 0.0)) {
          velocity[i][k] = -velocity[i][k];
        }
      }
      boxes[i].min += velocity[i];
      boxes[i].max += velocity[i];
    }
  }
};

template <typename Finder>
void Run(benchmark::State& state, bool coherent, Finder find) {
  const int n = static_cast<int>(state.range(0));
  std::vector<BenchScene> scenes;
  for (int k = 0; k < (coherent ? 1 : kRandomScenes); ++k) scenes.emplace_back(n, 12345u + k);
  std::vector<BodyPair> pairs;
  std::size_t next = 0;
  double total_pairs = 0.0;
  for (auto _ : state) {
    BenchScene& scene = scenes[next];
    next = (next + 1) % scenes.size();
    if (coherent) scene.Move();
    find(scene, &pairs);
    benchmark::DoNotOptimize(pairs.data());
    total_pairs += static_cast<double>(pairs.size());
  }
  state.counters["pairs"] = benchmark::Counter(total_pairs, benchmark::Counter::kAvgIterations);
}

void BM_BroadphaseNaiveRandom(benchmark::State& state) {
  NaiveBroadphase naive;
  Run(state, false, [&](const BenchScene& s, std::vector<BodyPair>* p) { naive.FindPairs(s.boxes, s.movable, p); });
}

void BM_BroadphaseSapRandom(benchmark::State& state) {
  SweepAndPrune sap;
  Run(state, false, [&](const BenchScene& s, std::vector<BodyPair>* p) {
    sap.Reset();
    sap.FindPairs(s.boxes, s.movable, p);
  });
}

void BM_BroadphaseNaiveCoherent(benchmark::State& state) {
  NaiveBroadphase naive;
  Run(state, true, [&](const BenchScene& s, std::vector<BodyPair>* p) { naive.FindPairs(s.boxes, s.movable, p); });
}

void BM_BroadphaseSapCoherent(benchmark::State& state) {
  SweepAndPrune sap;
  int64_t swaps = 0, calls = 0;
  Run(state, true, [&](const BenchScene& s, std::vector<BodyPair>* p) {
    sap.FindPairs(s.boxes, s.movable, p);
    swaps += sap.last_swaps();
    ++calls;
  });
  state.counters["swaps"] = calls > 0 ? static_cast<double>(swaps) / calls : 0.0;
}

void BM_BroadphaseSapCoherentRebuild(benchmark::State& state) {
  SweepAndPrune sap;
  Run(state, true, [&](const BenchScene& s, std::vector<BodyPair>* p) {
    sap.Reset();
    sap.FindPairs(s.boxes, s.movable, p);
  });
}

void Sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 30, 100, 300, 1000, 10000}) b->Arg(n);
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_BroadphaseNaiveRandom)->Apply(Sizes);
BENCHMARK(BM_BroadphaseNaiveRandom)->Arg(kLargeN)->Iterations(kLargeNIterations)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadphaseSapRandom)->Apply(Sizes)->Arg(kLargeN);
BENCHMARK(BM_BroadphaseNaiveCoherent)->Apply(Sizes);
BENCHMARK(BM_BroadphaseNaiveCoherent)->Arg(kLargeN)->Iterations(kLargeNIterations)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadphaseSapCoherent)->Apply(Sizes)->Arg(kLargeN);
BENCHMARK(BM_BroadphaseSapCoherentRebuild)->Apply(Sizes)->Arg(kLargeN);

}  // namespace
}  // namespace contactsim
