// xpbd's sub-steps (xpbd_method.h, step 2) as stages of one
// ParallelRunner::Stages call, as soft's (soft_stages.cpp): the per-body
// prediction and velocity update split over the bodies, the position sweep
// and the velocity pass colour by colour (block_colours.h: a colour's blocks
// share no dynamic body, so any thread may solve any of them in any order
// with the same result), the joints and their projection serial stages. One
// thread runs the same stages in the same order, so the state does not
// depend on the thread count.
#include <algorithm>
#include <atomic>
#include <vector>

#include "service/contact/colour_stages.h"
#include "service/contact/joints/joint_solver.h"
#include "service/contact/soft/soft_joints.h"
#include "service/contact/xpbd/xpbd_method.h"
#include "service/contact/xpbd/xpbd_restitution.h"
#include "service/contact/xpbd/xpbd_velocity_pass.h"

namespace contactsim {
namespace {

// bodies a thread takes at a time
constexpr int kXpbdBodyGrain = 128;
// Newton iterations of a sub-step's joint projection (xpbd_method.h, 2b):
// after the sweeps the joints are open by at most a few mm, which one step
// of Newton's method (quadratic) closes to below 1e-7 mm on the chains of
// joint_chain_scenarios_test.cpp; the next sub-step starts from there. A
// second iteration (to round-off) costs a second solve and row build for
// nothing that shows: 17 ms against 6.3 ms a step of the 100-link chain.
constexpr int kProjectionIterations = 1;
// m/s: the velocity pass sweeps again while a sweep changed some block's
// normal or sliding velocity by more than this
constexpr double kVelocitySweepTolerance = 1e-5;

}  // namespace

void XpbdMethod::DeriveVelocities(const World& world, double h, int begin, int end) {
  // velocities from what the solve moved (Algorithm 2, v = (x - x_prev) / h)
  for (int k = begin; k < end; ++k) {
    SoftBody& s = bodies_[k];
    const RigidBody& b = world.bodies()[k];
    if (!s.substepped || s.inv_mass == 0.0) continue;
    if (b.x == predicted_[k].x && b.q.coeffs() == predicted_[k].q.coeffs()) continue;
    Quat dq = b.q * predicted_[k].q.conjugate();
    if (dq.w() < 0.0) dq.coeffs() = -dq.coeffs();
    s.v += (b.x - predicted_[k].x) / h;
    s.w += (2.0 / h) * dq.vec();
  }
}

void XpbdMethod::RunSubsteps(World& world, int substeps, bool project_joints, ParallelRunner& runner) {
  auto& bodies = world.bodies();
  const double h = world.dt / substeps;
  XpbdSolve solve;
  solve.h = h;
  solve.alpha_tilde = params_.compliance / (h * h);
  // never below the resting overlap SubstepsFor allows a heavy body on a
  // light one, which the solve removes again every sub-step
  solve.max_push = std::max(params_.max_push_velocity * h, kMassRatioOverlap);
  solve.articulation = &articulation_;
  const double joint_alpha_tilde = params_.joint_compliance / (h * h);
  const double threshold = std::max(params_.restitution_threshold, 2.0 * world.gravity.norm() * h);
  // an approach that takes part at e = 0 (xpbd_restitution.h)
  const double strike = std::max(threshold, 2.0 * world.gravity.norm() * world.dt);

  using Fn = ParallelRunner::StageFn;
  const Fn predict_velocities = [&](int i, int j) { IntegrateSoftVelocities(world, h, i, j, bodies_); };
  const Fn predict_positions = [&](int i, int j) {
    IntegrateSoftPositions(h, i, j, world, bodies_, /*track_motion=*/false);
    for (int k = i; k < j; ++k) predicted_[k] = {bodies[k].x, bodies[k].q, bodies_[k].v, bodies_[k].w};
  };
  const Fn predict = [&](int i, int j) {
    predict_velocities(i, j);
    predict_positions(i, j);
  };
  // the jointed contacts' mobility at the predicted poses (XpbdArticulation::Refresh)
  const Fn refresh_articulation = [&](int, int) {
    articulation_.Refresh(world, bodies_);
    for (int k : jointed_blocks_) {
      RefreshJointedXpbdBlock(bodies_, articulation_, blocks_[k], &subsets_[k], &points_);
      RefreshJointedXpbdPatch(points_, bodies_, articulation_, &patches_[k]);
    }
  };
  const Fn begin_joints = [&](int, int) { joint_lambdas_.assign(world.joints().size(), XpbdJointLambda{}); };
  const Fn solve_joints = [&](int, int) { SolveXpbdJoints(world, joint_alpha_tilde, &joint_lambdas_); };
  const Fn solve_blocks = [&](int i, int j) {
    for (int k = i; k < j; ++k) {
      SolveXpbdBlockNormals(world, bodies_, solve, blocks_[k], subsets_[k], points_);
      SolveXpbdPatchFriction(world, bodies_, articulation_, blocks_[k], subsets_[k], patches_[k], points_);
    }
  };
  // the sub-step's multipliers start from zero as each block is first
  // solved (nothing reads a block's multipliers before that), which saves
  // a pass over the blocks a sub-step
  const Fn begin_and_solve_blocks = [&](int i, int j) {
    for (int k = i; k < j; ++k) {
      BeginXpbdSubstep(blocks_[k], &points_);
      BeginXpbdPatch(&patches_[k]);
    }
    solve_blocks(i, j);
  };
  // the jointed patches' static friction together after each sweep (xpbd_jointed_friction.h)
  const Fn solve_jointed_friction = [&](int, int) {
    jointed_friction_.Solve(world, bodies_, articulation_, jointed_blocks_, points_, patches_);
  };
  const bool jointed_friction = articulation_.active() && jointed_blocks_.size() >= 2;
  JointSolveOptions projection;
  projection.max_projection_iterations = kProjectionIterations;
  const Fn project = [&](int, int) { ProjectJointPositions(world, projection); };
  const Fn solve_ratios = [&](int, int) { ratio_.Solve(solve, bodies_, predicted_, world, points_); };
  const Fn derive_velocities = [&](int i, int j) { DeriveVelocities(world, h, i, j); };
  // joints with damping, friction or a drive: their velocity rows
  // (joints/joint_rows.h) solved with the joints' geometry on the
  // velocities the prediction moves the bodies by, after the forces' kick
  // and before the positions (xpbd_method.h, 2a): an implicit damper, a
  // friction that stops a joint before it moves, and a drive whose q' =
  // q + h v' is the actuator model's (joint_actuator.h)
  SoftJoints joint_velocities;
  const Fn solve_joint_dynamics = [&](int, int) { joint_velocities.SolveVelocities(world, h, bodies_); };
  const bool joint_dynamics = HasJointDynamics(world);
  const Fn gather_impacts = [&](int, int) {
    GatherXpbdImpacts(h, threshold, blocks_, points_, frames_, predicted_, bodies_, &impacts_, &deferred_, &struck_);
  };
  const int sweeps = params_.velocity_iterations;
  std::vector<Fn> velocity_sweeps;
  velocity_sweeps.reserve(sweeps);
  // per sweep: some block's velocities changed by more than
  // kVelocitySweepTolerance, so the next sweep runs
  std::vector<std::atomic<char>> unsettled(sweeps);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const XpbdVelocitySweep which{sweep == 0, sweeps == 1};
    velocity_sweeps.push_back([&, which, sweep](int i, int j) {
      if (sweep > 0 && !unsettled[sweep - 1].load(std::memory_order_relaxed)) return;
      const double largest = SolveXpbdContactVelocities(h, threshold, blocks_, deferred_, i, j, which, patches_,
                                                        subsets_, predicted_, articulation_, bodies_, &pass_blocks_,
                                                        &points_);
      if (largest > kVelocitySweepTolerance) unsettled[sweep].store(1, std::memory_order_relaxed);
    });
  }
  const Fn begin_sweeps = [&](int, int) {
    for (auto& flag : unsettled) flag.store(0, std::memory_order_relaxed);
  };
  const Fn report = [&](int i, int j) {
    ReportXpbdSubstepImpulses(h, blocks_, i, j, patches_, pass_blocks_, &points_);
  };
  pass_blocks_.resize(blocks_.size());
  const Fn solve_impacts = [&](int, int) { SolveXpbdImpacts(h, &impacts_, bodies_, &points_); };
  // components with restitution or a struck point take their velocities
  // from the impacts one at a time (xpbd_restitution.h); the standard
  // scenes' e = 0 at rest have none
  deferred_.assign(blocks_.size(), 0);
  const bool impacts = MarkXpbdStrikes(strike, points_, frames_, bodies_, &struck_);

  ColourStages list(&stages_, runner.threads());
  const int blocks = static_cast<int>(blocks_.size());
  const int n = static_cast<int>(bodies_.size());
  const bool joints = !world.joints().empty();
  predicted_.resize(bodies.size());
  // the time the start overlaps' slack is read at (XpbdSlack)
  const Fn advance_time = [&](int, int) { solve.elapsed += h; };
  const bool start_overlaps =
      std::any_of(points_.begin(), points_.end(), [](const XpbdPoint& p) { return p.slack0 > 0.0; });
  for (int sub = 0; sub < substeps; ++sub) {
    if (start_overlaps) list.AddSerial(advance_time);
    if (joint_dynamics) {
      list.Add(predict_velocities, 0, n, kXpbdBodyGrain);
      list.AddSerial(solve_joint_dynamics);
      list.Add(predict_positions, 0, n, kXpbdBodyGrain);
    } else {
      list.Add(predict, 0, n, kXpbdBodyGrain);
    }
    if (articulation_.active()) list.AddSerial(refresh_articulation);
    if (joints) list.AddSerial(begin_joints);
    for (int it = 0; it < params_.iterations; ++it) {
      if (joints) list.AddSerial(solve_joints);
      list.AddColours(it == 0 ? begin_and_solve_blocks : solve_blocks, colours_, blocks);
      if (jointed_friction) list.AddSerial(solve_jointed_friction);
    }
    if (ratio_.active()) list.AddSerial(solve_ratios);
    if (project_joints) list.AddSerial(project);
    list.Add(derive_velocities, 0, n, kXpbdBodyGrain);
    if (impacts) list.AddSerial(gather_impacts);
    if (sweeps > 1) list.AddSerial(begin_sweeps);
    for (const Fn& sweep : velocity_sweeps) list.AddColours(sweep, colours_, blocks);
    if (sweeps > 1) list.AddColours(report, colours_, blocks);
    if (impacts) list.AddSerial(solve_impacts);
  }
  runner.Stages(stages_);
  joint_velocities.StoreEfforts(world);
}

}  // namespace contactsim
