#include "service/contact/soft/wide/soft_wide_solver.h"

#include "service/contact/colour_stages.h"

namespace contactsim {
namespace {

// Indices a thread takes at a time (soft_stages.cpp's grains; a bundle is
// several manifolds).
constexpr int kWideSolverBodyGrain = 128;
constexpr int kBundleGrain = 64;

}  // namespace

void SoftWideSolver::Run(const SoftWideStep& step, const std::vector<SoftManifold>& manifolds,
                         const BlockColours& colours, ParallelRunner& runner, World& world,
                         std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) {
  const wide::WideKernels& kernels = wide::ChooseKernels(step.lanes);
  LoadWideBodies(world, bodies, runner, &bodies_);
  bundles_.Pack(points, manifolds, colours, bodies, step.friction_points, kernels.width, bodies_.dummy());
  wide::WideView view = bundles_.View(bodies_.state.data());
  static_assert(sizeof(WideBodyMotion) % sizeof(float) == 0, "a body's inertia lies a whole number of floats on");
  view.inv_inertia = bodies_.motion[0].inv_inertia.data();
  view.inertia_stride = static_cast<int>(sizeof(WideBodyMotion) / sizeof(float));
  const float h = static_cast<float>(step.h);
  wide::WidePass solve;
  solve.inv_h = static_cast<float>(step.solve.inv_h);
  solve.max_push_velocity = static_cast<float>(step.solve.max_push_velocity);
  wide::WidePass relax = solve;
  relax.use_bias = false;
  // as the double path's relax pass (soft_stages.cpp; no joints here)
  relax.hold_pushing_gaps = true;

  using Fn = ParallelRunner::StageFn;
  const Fn integrate_velocities = [&](int i, int j) { IntegrateWideVelocities(h, i, j, bodies_); };
  const Fn integrate_positions = [&](int i, int j) { IntegrateWidePositions(h, i, j, bodies_); };
  const Fn warm_start = [&](int i, int j) { kernels.warm_start(view, i, j); };
  const Fn solve_bundles = [&](int i, int j) { kernels.solve(view, solve, i, j); };
  const Fn relax_bundles = [&](int i, int j) { kernels.solve(view, relax, i, j); };
  const Fn accumulate = [&](int i, int j) { kernels.accumulate(view, i, j); };
  const Fn prepare = [&](int i, int j) { kernels.prepare(view, i, j); };

  ColourStages list(&stages_, runner.threads());
  const int count = static_cast<int>(bodies.size());
  const int bundles = bundles_.bundles();
  list.Add(prepare, 0, bundles, kBundleGrain);
  for (int sub = 0; sub < step.substeps; ++sub) {
    list.Add(integrate_velocities, 0, count, kWideSolverBodyGrain);
    list.AddColours(warm_start, bundles_.colours(), bundles);
    list.AddColours(solve_bundles, bundles_.colours(), bundles);
    list.Add(integrate_positions, 0, count, kWideSolverBodyGrain);
    for (int it = 0; it < step.relax_iterations; ++it) list.AddColours(relax_bundles, bundles_.colours(), bundles);
    list.Add(accumulate, 0, bundles, kBundleGrain);
  }
  runner.Stages(stages_);
  bundles_.Unpack(points);
  StoreWideBodies(bodies_, runner, bodies, world);
}

}  // namespace contactsim
