#include "bench/tools/scene_bench/run_scene.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>

#include "bench/tools/scene_bench/scene_metrics.h"

namespace contactsim::bench {
namespace {

using Clock = std::chrono::steady_clock;

std::string BaseName(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  const size_t dot = name.rfind(".pbtxt");
  return dot == std::string::npos ? name : name.substr(0, dot);
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Folds the method's report of step `done` (1-based) into the run's.
void Accumulate(const std::optional<StepStats>& stats, int done, BenchResult* r) {
  if (!stats) return;
  const double n = stats->iterations;
  r->iterations_mean = r->iterations_mean.value_or(0.0) + (n - r->iterations_mean.value_or(0.0)) / done;
  r->iterations_max = std::max(r->iterations_max.value_or(n), n);
  r->residual_min = std::min(r->residual_min.value_or(stats->residual), stats->residual);
  r->stiffness_max = std::max(r->stiffness_max.value_or(stats->stiffness), stats->stiffness);
}

}  // namespace

double PeakRssMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

BenchResult RunScene(const BenchOptions& options, const SceneSpec& scene, const World& world,
                     const EngineFactory& factory, const ProgressFn& progress) {
  BenchResult r;
  r.scene = BaseName(options.scene);
  r.method = options.method;
  r.bodies = static_cast<int>(world.bodies().size());
  r.steps = options.steps > 0 ? options.steps : scene.steps;
  r.dt = world.dt;
  for (int repeat = 0; repeat < std::max(1, options.repeat); ++repeat) {
    std::unique_ptr<SceneEngine> engine;
    const Status st = factory(options, scene, world, &engine);
    if (!st.ok()) {
      r.status = "error: " + st.message();
      break;
    }
    r.params = engine->Params();
    SceneMetrics metrics;
    metrics.Start(engine->Sync());
    const bool measure = repeat == 0;
    Clock::duration stepping{};
    int done = 0;
    std::string failure;
    while (done < r.steps) {
      const Clock::time_point t0 = Clock::now();
      engine->Step();
      stepping += Clock::now() - t0;
      ++done;
      const World& state = engine->Sync();
      failure = engine->Failure();
      if (failure.empty()) failure = metrics.Check(state);
      if (measure && failure.empty()) metrics.Observe(state);
      if (measure) Accumulate(engine->LastStats(), done, &r);
      if (progress) progress(repeat, done, r.steps);
      if (!failure.empty()) break;
      if (options.max_seconds > 0.0 && std::chrono::duration<double>(stepping).count() > options.max_seconds) {
        failure = "timeout: " + std::to_string(done) + " of " + std::to_string(r.steps) + " steps in " +
                  std::to_string(static_cast<int>(options.max_seconds)) + " s";
        break;
      }
    }
    r.ms_per_step_repeats.push_back(std::chrono::duration<double, std::milli>(stepping).count() /
                                    std::max(1, done));
    if (measure) {
      r.steps_done = done;
      r.max_penetration = metrics.max_penetration();
      r.min_distance = metrics.min_distance();
      r.fell_through = metrics.fell_through();
      r.final_kinetic_energy = metrics.final_kinetic_energy();
      r.top_displacement = metrics.top_displacement();
      r.rebound_height = metrics.rebound_height();
      r.sleeping = engine->Sleeping();
    }
    if (!failure.empty()) {
      r.status = failure + " (at step " + std::to_string(done) + ")";
      if (failure.rfind("timeout", 0) == 0) r.status = failure;
      break;  // a failing run fails the same way again: no more repeats
    }
  }
  if (!r.ms_per_step_repeats.empty()) {
    r.ms_per_step = Median(r.ms_per_step_repeats);
    r.ms_per_step_min = *std::min_element(r.ms_per_step_repeats.begin(), r.ms_per_step_repeats.end());
    r.ms_per_step_max = *std::max_element(r.ms_per_step_repeats.begin(), r.ms_per_step_repeats.end());
  }
  r.peak_rss_mb = PeakRssMb();
  return r;
}

}  // namespace contactsim::bench
