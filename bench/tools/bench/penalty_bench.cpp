// Penalty method: the largest stable kp at dt = 1/240 s for a stack of five
// boxes, per integrator, and the cost of a step.
//
// Scene: five 0.2 m boxes (8 kg, mu = 0.5, e = 0.5) on the ground plane,
// either touching ("stack") or with 1 cm gaps ("dropped": every contact
// starts with an impact). Friction stiffness fixed at 1e5 N/m (stable for
// both integrators, so that the search measures kp alone); penalty defaults
// otherwise (restitution from the materials, margin 5 mm, 1 sub-step).
// "Stable" over 2 s (480 steps) means: every state finite, max penetration
// below half the box size (0.1 m), and kinetic + potential energy never more
// than 1% above its start (a stack that launches boxes has shallow contacts
// but gains energy).
// The search bisects log10 kp between 1e4 N/m (stable for every integrator:
// softer springs let the stack sink past half a box) and 1e15 N/m (the top
// of the kp range) to 0.01 decades, assuming stability is monotone in kp; a
// kp_max of 1e15 means no instability was found in the range.
// Run (see BENCHMARKS.md, "Penalty: largest stable kp"):
//   build/bin/contactsim-bench --benchmark_filter=Penalty
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "service/contact/penalty/penalty_method.h"
#include "service/physics/body_settings.h"

namespace contactsim {
namespace {

constexpr double kHalf = 0.1;         // m, half the box size
constexpr int kSteps = 480;           // 2 s at 1/240 s
constexpr double kEnergySlack = 0.01; // of the initial energy
constexpr double kLogLo = 4.0, kLogHi = 15.0, kLogTolerance = 0.01;
// the scene's mu = 0.5, e = 0.5 (above); e sets penalty's damping
constexpr Material kStackMaterial{0.5, 0.5};

struct Config {
  const char* integrator;
  const char* theta;
};
const Config kConfigs[] = {{"explicit", "1"}, {"implicit", "1"}, {"implicit", "0.5"}};

void BuildStack(World& world, double gap) {
  BodySettings ground;
  ground.shape = ShapeType::kPlane;
  RigidBody b;
  CreateBody(ground, kStackMaterial, &b);
  world.AddBody(b);
  for (int i = 0; i < 5; ++i) {
    BodySettings s;
    s.shape = ShapeType::kBox;
    s.half_extents = Vec3::Constant(kHalf);
    s.position = Vec3(0, 0, kHalf + i * (2.0 * kHalf + gap));
    CreateBody(s, kStackMaterial, &b);
    world.AddBody(b);
  }
}

double Energy(const World& world) {
  double e = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic()) e += b.KineticEnergy() - b.mass * world.gravity.dot(b.x);
  }
  return e;
}

std::string Text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool IsStable(const Config& config, double kp, double gap) {
  World world;
  CollisionDetector detector;
  PenaltyMethod method;
  ContactSet contacts;
  if (!method.SetParams({{"integrator", config.integrator}, {"theta", config.theta}, {"kp", Text(kp)},
                         {"friction_stiffness", "1e5"}}).ok()) {
    return false;
  }
  BuildStack(world, gap);
  const double e0 = Energy(world);
  for (int i = 0; i < kSteps; ++i) {
    const StepStats stats = method.Step(world, detector, &contacts);
    if (!(stats.max_penetration < kHalf)) return false;  // also catches NaN
    for (const RigidBody& b : world.bodies()) {
      if (!b.x.allFinite() || !b.P.allFinite() || !b.L.allFinite()) return false;
    }
    if (!(Energy(world) <= e0 + kEnergySlack * std::abs(e0))) return false;
  }
  return true;
}

// state.range(0): config index; range(1): gap in mm
void BM_PenaltyLargestStableKp(benchmark::State& state) {
  const Config& config = kConfigs[state.range(0)];
  const double gap = 1e-3 * state.range(1);
  double lo = kLogLo, hi = kLogHi;
  int runs = 0;
  for (auto _ : state) {
    lo = kLogLo;
    hi = kLogHi;
    runs = 2;
    if (!IsStable(config, std::pow(10.0, lo), gap)) {
      state.SkipWithError("the lower bound 1e4 N/m is not stable");
      return;
    }
    if (IsStable(config, std::pow(10.0, hi), gap)) {
      lo = hi;
    } else {
      while (hi - lo > kLogTolerance) {
        const double mid = 0.5 * (lo + hi);
        (IsStable(config, std::pow(10.0, mid), gap) ? lo : hi) = mid;
        ++runs;
      }
    }
  }
  state.SetLabel(std::string(config.integrator) + " theta=" + config.theta +
                 (gap > 0.0 ? " dropped" : " stack"));
  state.counters["kp_max"] = std::pow(10.0, lo);
  state.counters["log10_kp_max"] = lo;
  state.counters["runs"] = runs;
}

// Cost of one step of the touching stack at kp = 1e5 N/m (stable for all).
void BM_PenaltyStackStep(benchmark::State& state) {
  const Config& config = kConfigs[state.range(0)];
  World world;
  CollisionDetector detector;
  PenaltyMethod method;
  ContactSet contacts;
  method.SetParams({{"integrator", config.integrator}, {"theta", config.theta}, {"kp", "1e5"},
                    {"friction_stiffness", "1e5"}});
  BuildStack(world, 0.0);
  for (int i = 0; i < 240; ++i) method.Step(world, detector, &contacts);  // settle
  int iterations = 0;
  for (auto _ : state) iterations += method.Step(world, detector, &contacts).iterations;
  state.SetLabel(std::string(config.integrator) + " theta=" + config.theta);
  state.counters["active_set_passes"] =
      benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}

BENCHMARK(BM_PenaltyLargestStableKp)
    ->ArgsProduct({{0, 1, 2}, {0, 10}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PenaltyStackStep)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace contactsim
