// The measuring loop shared by contactsim-bench and the peer runners: build
// the engine afresh for each repeat, time the stepping calls alone
// (steady_clock around each Step(), summed), and measure the physics on the
// first repeat (scene_metrics.h; the engines are deterministic, so the other
// repeats would measure the same). Every repeat checks every step for NaN
// and explosion and stops there.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bench/tools/scene_bench/scene_engine.h"

namespace contactsim::bench {

struct BenchResult {
  std::string engine;             // "contactsim", "bullet", "ode", "mujoco"
  std::string scene;              // the scene file's base name, without .pbtxt
  std::string method;
  ParamMap params;
  int threads = 1;                // of contactsim's collision detector (--threads)
  bool sleep = false;             // settled islands slept (--sleep)
  bool manifold_reuse = false;    // touching polyhedron pairs kept their manifolds (contactsim's default)
  int sleeping = 0;               // bodies asleep at the end of the first repeat
  int bodies = 0;
  int steps = 0;                  // asked for
  int steps_done = 0;             // of the first repeat (less than `steps` after a failure)
  double dt = 0.0;                // s
  std::vector<double> ms_per_step_repeats;
  double ms_per_step = 0.0;       // median of the repeats
  double ms_per_step_min = 0.0;
  double ms_per_step_max = 0.0;
  double max_penetration = 0.0;   // m
  std::optional<double> min_distance;      // m, < 0 a penetration; none: never within 1 cm
  std::optional<int> fell_through;     // bodies once below a mesh or heightfield; none: the scene has none
  double final_kinetic_energy = 0.0;  // J
  std::optional<double> top_displacement;  // m
  std::optional<double> rebound_height;    // m
  // the method's own report over the measured steps (contactsim engines;
  // none for the peers): solver iterations per step (barrier: Newton
  // iterations), the smallest residual (barrier: its own smallest distance,
  // m) and the largest stiffness (barrier: kappa, N/m)
  std::optional<double> iterations_mean, iterations_max, residual_min, stiffness_max;
  double peak_rss_mb = 0.0;       // MiB, getrusage
  std::string status = "ok";      // "ok", or "nan: ...", "exploded: ...", "timeout: ...", "error: ..."
};

// Called after each step with (repeat, step, steps) so a caller can draw a
// progress bar; not timed.
using ProgressFn = std::function<void(int repeat, int step, int steps)>;

BenchResult RunScene(const BenchOptions& options, const SceneSpec& scene, const World& world,
                     const EngineFactory& factory, const ProgressFn& progress);

// Peak resident set of this process so far (MiB).
double PeakRssMb();

}  // namespace contactsim::bench
