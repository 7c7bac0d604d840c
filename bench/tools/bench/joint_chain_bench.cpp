// Joint solve of a hanging chain: the tree solver (Baraff 1996, O(n)) against
// the dense LDLT of J M^-1 J^T (O(n^3)), for chains of 10 to 1,000 links.
//
// Scene: n capsules (radius 2 cm, 12 cm between joint points) joined by ball
// joints (3 rows each) and hung from the world; every link has a random
// velocity (seeded), so the right-hand side is not trivial. Timed: one solve
// of (J M^-1 J^T + R) lambda = b for the velocity rows (SolveJointSystem),
// the rows built once outside the loop. "rows/step" adds building the rows,
// solving and applying the impulses (ApplyJointImpulses) for the tree solver,
// the cost a contact method pays per step.
// Run (see BENCHMARKS.md, "Joint chains"):
//   build/bin/contactsim-bench --benchmark_filter=JointChain
#include <benchmark/benchmark.h>

#include <random>

#include "service/contact/joints/joint_solver.h"
#include "service/physics/body_settings.h"

namespace contactsim {
namespace {

struct Chain {
  World world;
  std::vector<SolverBody> bodies;
  std::vector<ConstraintRow> rows;
  std::vector<JointBlock> blocks;
  Eigen::VectorXd b;
};

void BuildChain(int n, Chain* c) {
  const double r = 0.02, hl = 0.04, pitch = 2.0 * (r + hl);
  const Vec3 top(0, 0, n * pitch + 1.0);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  BodyId above = kWorldBody;
  for (int i = 0; i < n; ++i) {
    BodySettings s;
    s.shape = ShapeType::kCapsule;
    s.radius = r;
    s.half_length = hl;
    s.position = top - Vec3(0, 0, (i + 0.5) * pitch);
    s.linear_velocity = Vec3{u(rng), u(rng), u(rng)};
    s.angular_velocity = Vec3{u(rng), u(rng), u(rng)};
    RigidBody body;
    CreateBody(s, Material{}, &body);
    const BodyId id = c->world.AddBody(body);
    JointSettings j;
    j.kind = JointKind::kBall;
    j.body_a = id;
    j.body_b = above;
    j.anchor = top - Vec3(0, 0, i * pitch);
    JointId joint;
    c->world.AddJoint(j, &joint);
    above = id;
  }
  LoadSolverBodies(c->world, &c->bodies);
  AppendJointRows(c->world, c->bodies, c->world.dt, JointRowMode::kVelocity, &c->rows, &c->blocks);
  c->b.resize(c->rows.size());
  for (size_t k = 0; k < c->rows.size(); ++k) c->b[k] = c->rows[k].rhs - c->rows[k].Velocity(c->bodies);
}

void BM_JointChainSolve(benchmark::State& state, JointSolverKind solver) {
  Chain c;
  BuildChain(static_cast<int>(state.range(0)), &c);
  for (auto _ : state) {
    Eigen::VectorXd lambda = SolveJointSystem(c.rows, c.blocks, c.bodies, c.b, solver);
    benchmark::DoNotOptimize(lambda.data());
  }
  state.counters["rows"] = static_cast<double>(c.rows.size());
  state.SetComplexityN(state.range(0));
}

void BM_JointChainStep(benchmark::State& state) {
  Chain c;
  BuildChain(static_cast<int>(state.range(0)), &c);
  std::vector<SolverBody> bodies;
  for (auto _ : state) {
    bodies = c.bodies;
    const JointStats stats = ApplyJointImpulses(c.world, c.world.dt, bodies);
    benchmark::DoNotOptimize(stats.rows);
  }
  state.SetComplexityN(state.range(0));
}

BENCHMARK_CAPTURE(BM_JointChainSolve, tree, JointSolverKind::kTree)
    ->Arg(10)->Arg(100)->Arg(1000)->Complexity(benchmark::oN)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_JointChainSolve, dense, JointSolverKind::kDense)
    ->Arg(10)->Arg(100)->Arg(1000)->Complexity(benchmark::oNCubed)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_JointChainStep)->Arg(10)->Arg(100)->Arg(1000)->Complexity(benchmark::oN)
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace contactsim
