// The soft step's sub-steps (soft_method.h, steps 2 to 3) as stages of one
// ParallelRunner::Stages call: per-body work split over the bodies, and
// every pass over the contacts colour by colour (block_colours.h), whose
// blocks share no dynamic body and so run on any thread in any order with
// the same result; the direct solve of heavy-on-light contacts and the
// joints are serial stages. One thread runs the same stages in the same
// order, so the state does not depend on the thread count.
#include <algorithm>
#include <string>

#include "service/contact/colour_stages.h"
#include "service/contact/soft/soft_method.h"
#include "service/contact/soft/soft_restitution.h"

namespace contactsim {
namespace {

// Indices a thread takes at a time: enough work to pay for the atomic
// counter, small enough that two threads finish a colour together.
constexpr int kSoftStageBodyGrain = 128;
constexpr int kPointGrain = 512;

// The bodies in the order of their first block from the top (`blocks` in
// the sweep order, before the colouring), then the others in index order.
// Thread w takes about the same part of every colour pass, the part from
// w / threads of the way down (parallel_stages.cpp), so walked in this
// order the body stages hand it about the bodies its blocks write, and a
// body's cache lines stay in one core's cache from stage to stage; each
// body's update is its own, so the order changes no result.
void OrderBodiesFromTheTop(const std::vector<SoftManifold>& blocks, const std::vector<SoftPoint>& points,
                           std::vector<char>* seen, std::vector<int>* order) {
  const int n = static_cast<int>(seen->size());
  std::fill(seen->begin(), seen->end(), 0);
  order->clear();
  for (const SoftManifold& m : blocks) {
    for (int i : {points[m.first].a, points[m.first].b}) {
      if ((*seen)[i] != 0) continue;
      (*seen)[i] = 1;
      order->push_back(i);
    }
  }
  for (int i = 0; i < n; ++i) {
    if ((*seen)[i] == 0) order->push_back(i);
  }
}

}  // namespace

void SoftMethod::RunSubsteps(World& world, ParallelRunner& runner) {
  const double h = world.dt / params_.substeps;
  SubspaceOptions direct;
  direct.mass_ratio = params_.direct_mass_ratio;
  direct.max_rows = params_.direct_max_rows;
  // every row free at first, held one a pass: 8 passes left a light box
  // between two 1,000 times heavier ones sinking 0.27 m, 32 let some
  // bridges of MassRatioSupportTest slide; 12-20 hold all of them
  direct.start_free = true;
  direct.passes = 16;
  // the guard's re-solve from zero impulses loses what the pass found: with
  // it the 1:1000 bridge of MassRatioBridgeTest slid off its supports
  // (docs/methods/soft.md, "Heavy on light")
  direct.energy_guard = false;
  ratio_solve_.Select(direct, bodies_, points_);
  const bool float_path = params_.precision == "float" && SoftWideSolver::Applies(world, ratio_solve_.active());
  if (wide_prepare_ && !float_path) {
    // the double path's rows, as Prepare makes them for precision=double
    PrepareSoftRows(bodies_, FrictionPoints(), runner, &points_);
  }
  ratio_solve_.Stiffen(bodies_, points_);
  jointed_solve_.Prepare(world, direct, bodies_, points_);
  body_seen_.resize(bodies_.size());
  OrderBodiesFromTheTop(manifolds_, points_, &body_seen_, &body_order_);
  ColourManifolds();
  SoftPass solve;
  solve.inv_h = 1.0 / h;
  solve.max_push_velocity = params_.max_push_velocity;
  if (float_path) {
    SoftWideStep wide{h, params_.substeps, params_.relax_iterations, solve, 0};
    if (params_.float_lanes != "widest") wide.lanes = std::stoi(params_.float_lanes);
    wide.friction_points = FrictionPoints();
    wide_.Run(wide, manifolds_, colours_, runner, world, points_, bodies_);
    const double threshold = RestitutionThreshold(world);
    if (!SoftStepNeedsRestitution(threshold, points_, bodies_)) return;
    // restitution's normal rows in double as the double path's (from the
    // inverse inertias at the step's start, which the float path leaves in
    // bodies_), its friction rows the float path's (soft_wide_solver.h)
    PrepareSoftRows(bodies_, FrictionPoints(), runner, &points_, /*friction_rows=*/false);
    wide_.UnpackFrictionRows(points_);
    RestituteSoftPoints(threshold, world, manifolds_, points_, bodies_, &impacts_);
    return;
  }
  // K^-1 of the blocks, from their points' copies as they move into the
  // manifolds' order; the ratio and joint-contact solves hold points by
  // their contact index, so there they stay where they are
  if (!ratio_solve_.active() && !jointed_solve_.active()) {
    point_order_.Apply(runner, &manifolds_, &points_);
  } else {
    InvertSoftManifolds(points_, runner, &manifolds_);
  }
  SoftPass relax = solve;
  relax.use_bias = false;
  relax.hold_pushing_gaps = true;
  // the heavy-on-light direct solve aims at the gaps as before (holding them
  // there let the 1:1000 sandwich sink 12 mm and the bridge rise 3.5 mm),
  // except where the joint-contact solve follows it on the same points and
  // holds them: aiming apart, the two moved two 5 kg loads on a welded
  // 0.5 kg plank 7.3 mm in 3 s, aiming alike 1.6 mm
  SoftPass relax_direct = relax;
  relax_direct.hold_pushing_gaps = jointed_solve_.active();

  using Fn = ParallelRunner::StageFn;
  points_of_bodies_.Build(points_, bodies_, point_order_.PointsOfContacts());
  // each body's velocity from its forces, then its points' warm start: one
  // stage, each body's update its own and in the same order as two
  // stages', so the bodies are read once for both
  const Fn integrate_and_warm_start = [&](int i, int j) {
    IntegrateSoftVelocities(world, h, i, j, bodies_, &body_order_);
    for (int q = i; q < j; ++q) WarmStartSoftBody(body_order_[q], points_of_bodies_, points_, bodies_);
  };
  const Fn solve_blocks = [&](int i, int j) { SolveSoftManifolds(solve, manifolds_, i, j, points_, bodies_); };
  const Fn solve_ratio = [&](int, int) { ratio_solve_.Solve(solve, points_, bodies_); };
  const Fn begin_joints = [&](int, int) { joints_.Begin(world, h, bodies_); };
  const Fn solve_joints = [&](int, int) { joints_.SolveVelocities(world, h, bodies_); };
  const Fn relax_joints = [&](int, int) { joints_.SolveVelocities(world, h, bodies_, /*relax=*/true); };
  const bool joint_dynamics = HasJointDynamics(world);
  const Fn integrate_positions = [&](int i, int j) {
    IntegrateSoftPositions(h, i, j, world, bodies_, /*track_motion=*/true, &body_order_);
  };
  const Fn relax_blocks = [&](int i, int j) { SolveSoftManifolds(relax, manifolds_, i, j, points_, bodies_); };
  const Fn relax_ratio = [&](int, int) { ratio_solve_.Solve(relax_direct, points_, bodies_); };
  const Fn solve_jointed = [&](int, int) { jointed_solve_.Solve(world, h, solve, points_, bodies_); };
  const Fn relax_jointed = [&](int, int) { jointed_solve_.Solve(world, h, relax, points_, bodies_); };
  const Fn accumulate = [&](int i, int j) {
    for (int k = i; k < j; ++k) AccumulateSoftTotals(points_[k]);
  };
  // Where nothing after the relax passes changes an impulse (no joints, no
  // direct solve), a sub-step's last relax pass adds each block's impulses
  // to its points' totals as it relaxes the block: the same sums, on the
  // thread that holds the points, without a pass over the points in contact
  // order (another split of them over the threads) and its meeting.
  const bool fuse_accumulate = params_.relax_iterations > 0 && world.joints().empty() && !ratio_solve_.active() &&
                               !jointed_solve_.active();
  // Block by block, while the block's points are still in the first-level
  // cache (a chunk's worth of blocks relaxed first fetched them again: 4%
  // more first-level misses a 10,000-box step, BENCHMARKS.md "Scaling:
  // 1,000 to 10,000 bodies").
  const Fn relax_and_accumulate = [&](int i, int j) {
    for (int k = i; k < j; ++k) {
      SolveSoftManifolds(relax, manifolds_, k, k + 1, points_, bodies_);
      for (int p = manifolds_[k].first; p < manifolds_[k].first + manifolds_[k].count; ++p) {
        AccumulateSoftTotals(points_[p]);
      }
    }
  };
  const double threshold = RestitutionThreshold(world);
  const Fn restitute = [&](int, int) {
    RestituteSoftPoints(threshold, world, manifolds_, points_, bodies_, &impacts_);
  };

  ColourStages list(&stages_, runner.threads());
  const int blocks = static_cast<int>(manifolds_.size());
  const int bodies = static_cast<int>(bodies_.size());
  const bool joints = !world.joints().empty();
  // contacts and joints as two blocks of a Gauss-Seidel iteration, taken in
  // turn joint_passes times (contact/joints/joint_block.h)
  const int joint_passes = joints ? params_.joint_passes : 1;
  for (int sub = 0; sub < params_.substeps; ++sub) {
    list.Add(integrate_and_warm_start, 0, bodies, kSoftStageBodyGrain);
    if (joint_dynamics) list.AddSerial(begin_joints);
    // the heavy-on-light direct solve, a dense factorisation, once a stage:
    // before the stage's last joint solve
    for (int pass = 0; pass < joint_passes; ++pass) {
      list.AddColours(solve_blocks, colours_, blocks);
      if (ratio_solve_.active() && pass + 1 == joint_passes) list.AddSerial(solve_ratio);
      if (jointed_solve_.active() && pass + 1 == joint_passes) list.AddSerial(solve_jointed);
      if (joints) list.AddSerial(solve_joints);
    }
    list.Add(integrate_positions, 0, bodies, kSoftStageBodyGrain);
    for (int pass = 0; pass < joint_passes; ++pass) {
      for (int it = 0; it < params_.relax_iterations; ++it) {
        const bool last_relax = it + 1 == params_.relax_iterations;
        list.AddColours(fuse_accumulate && last_relax ? relax_and_accumulate : relax_blocks, colours_, blocks);
      }
      const bool last = pass + 1 == joint_passes;
      if (ratio_solve_.active() && params_.relax_iterations > 0 && last) list.AddSerial(relax_ratio);
      if (jointed_solve_.active() && params_.relax_iterations > 0 && last) list.AddSerial(relax_jointed);
      if (joints) list.AddSerial(relax_joints);
    }
    if (!fuse_accumulate) list.Add(accumulate, 0, static_cast<int>(points_.size()), kPointGrain);
  }
  // a step at rest leaves it after one look at the points (soft_restitution.h)
  list.AddSerial(restitute);
  runner.Stages(stages_);
}

}  // namespace contactsim
