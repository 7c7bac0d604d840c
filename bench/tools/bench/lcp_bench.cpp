// lcp method: cost of a step, and the time spent in the contact solve.
//
// Scenes (dt = 1/240 s, mu = 0.5, e = 0):
//  * pyramid: 20 rows of unit boxes (210 boxes, base of 20 touching boxes,
//    rows offset 0.5 m) on the ground plane, the stacking scene;
//    240 steps (1 s) are run before timing so that the warm start and the
//    separating-axis cache are in their steady state;
//  * sphere pile: 1,000 spheres of radius 0.1 m in a 10 x 10 x 10 lattice
//    (spacing 0.21 m, alternate layers shifted 0.05 m so that they collapse)
//    dropped on the plane; timed from 1 s after the drop;
//  * stack: n boxes of 0.2 m on the plane, for lemke and pgs side by side.
// The time column is the cost of one step. Counters: contacts, solver
// iterations (sweeps or pivots) per step, top_drift_mm (pyramid: how far
// the top box has moved since the start), lemke_fallbacks (steps that
// Lemke did not solve and PGS did).
// Run (see BENCHMARKS.md, "lcp: pyramid, sphere pile and small stacks"):
//   build/bin/contactsim-bench --benchmark_filter=Lcp
#include <benchmark/benchmark.h>

#include <string>

#include "service/contact/lcp/lcp_method.h"
#include "service/physics/body_settings.h"

namespace contactsim {
namespace {

void AddGroundPlane(World& world) {
  BodySettings ground;
  ground.shape = ShapeType::kPlane;
  ground.restitution = 0.0;
  RigidBody b;
  CreateBody(ground, Material{}, &b);
  world.AddBody(b);
}

BodyId AddBody(World& world, ShapeType shape, double size, const Vec3& p) {
  BodySettings s;
  s.shape = shape;
  if (shape == ShapeType::kBox) s.half_extents = Vec3::Constant(size);
  if (shape == ShapeType::kSphere) s.radius = size;
  s.position = p;
  s.restitution = 0.0;
  RigidBody b;
  CreateBody(s, Material{}, &b);
  return world.AddBody(b);
}

BodyId BuildPyramid(World& world, int rows) {
  AddGroundPlane(world);
  BodyId top = 0;
  for (int row = 0; row < rows; ++row) {
    for (int i = 0; i < rows - row; ++i) top = AddBody(world, ShapeType::kBox, 0.5, Vec3(i + 0.5 * row, 0, 0.5 + row));
  }
  return top;
}

void BuildSpherePile(World& world) {
  AddGroundPlane(world);
  for (int k = 0; k < 10; ++k) {
    const double shift = (k % 2) * 0.05;
    for (int j = 0; j < 10; ++j) {
      for (int i = 0; i < 10; ++i) {
        AddBody(world, ShapeType::kSphere, 0.1, Vec3(0.21 * i + shift, 0.21 * j + shift, 0.11 + 0.21 * k));
      }
    }
  }
}

void BuildStack(World& world, int n) {
  AddGroundPlane(world);
  for (int i = 0; i < n; ++i) AddBody(world, ShapeType::kBox, 0.1, Vec3(0, 0, 0.1 + 0.2 * i));
}

struct LcpRun {
  World world;
  CollisionDetector detector;
  LcpMethod method;
  ContactSet contacts;
  StepStats Step() { return method.Step(world, detector, &contacts); }
};

void TimeSteps(benchmark::State& state, LcpRun& run) {
  long steps = 0, iterations = 0;
  for (auto _ : state) {
    iterations += run.Step().iterations;
    ++steps;
  }
  state.counters["contacts"] = static_cast<double>(run.contacts.size());
  state.counters["iterations"] = static_cast<double>(iterations) / std::max(1L, steps);
}

// range(0): warm start on (1) or off (0)
void BM_LcpPyramidPgs(benchmark::State& state) {
  LcpRun run;
  run.method.SetParams({{"solver", "pgs"}, {"warm_start", state.range(0) ? "true" : "false"}});
  const BodyId top = BuildPyramid(run.world, 20);
  const Vec3 top0 = run.world.Find(top)->x;
  for (int i = 0; i < 240; ++i) run.Step();
  TimeSteps(state, run);
  state.counters["top_drift_mm"] = 1e3 * (run.world.Find(top)->x - top0).norm();
  state.SetLabel(state.range(0) ? "warm start" : "cold start");
}
BENCHMARK(BM_LcpPyramidPgs)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

void BM_LcpSpherePilePgs(benchmark::State& state) {
  LcpRun run;
  BuildSpherePile(run.world);
  for (int i = 0; i < 240; ++i) run.Step();
  TimeSteps(state, run);
}
BENCHMARK(BM_LcpSpherePilePgs)->Unit(benchmark::kMillisecond);

// range(0): solver (0 pgs, 1 lemke); range(1): boxes in the stack
void BM_LcpStack(benchmark::State& state) {
  LcpRun run;
  const char* solver = state.range(0) ? "lemke" : "pgs";
  run.method.SetParams({{"solver", solver}});
  BuildStack(run.world, static_cast<int>(state.range(1)));
  for (int i = 0; i < 60; ++i) run.Step();
  TimeSteps(state, run);
  state.counters["lemke_fallbacks"] = run.method.lemke_fallbacks();
  state.SetLabel(solver);
}
BENCHMARK(BM_LcpStack)->ArgsProduct({{0, 1}, {1, 2, 4, 8}})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace contactsim
