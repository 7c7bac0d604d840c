// The soft step's sub-steps in single precision over SIMD lanes (soft
// parameter precision=float): the stages of soft_stages.cpp with the
// contact constraints packed into bundles of 4 or 8 manifolds of one colour
// (soft_wide_bundles.h), and the bodies in a compact float array
// (soft_wide_bodies.h) read from the world once at the step's start and
// written back once at its end: Box2D v3 and Box3D's wide solver (Catto,
// "Solver2D", 2024; box2d src/contact_solver.c).
//
// It takes the worlds without joints and without a heavy-on-light
// component (soft_ratio_solve.h), whose serial direct solves read the
// double state pass by pass; those step on the double path. Restitution
// runs after it on the double state, as on the double path.
//
// Every lane is one manifold's own arithmetic, the colours fix which
// manifolds go before which, and a colour's bundles share no movable
// body: the result is the same bit for bit on any number of threads and at
// either width.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/soft/soft_manifold.h"
#include "service/contact/soft/wide/soft_wide_bodies.h"
#include "service/contact/soft/wide/soft_wide_bundles.h"
#include "service/contact/soft/wide/soft_wide_kernels.h"

namespace contactsim {

// What one step of the float path needs from the soft method.
struct SoftWideStep {
  double h = 0.0;             // s, sub-step
  int substeps = 1;
  int relax_iterations = 1;
  SoftPass solve;             // the solve's targets; the relax pass drops the bias
  int lanes = 0;              // 4 or 8; 0: the widest the processor runs
  // where each point's friction acts (patch_torsion.h); null: at its anchors
  const std::vector<Vec3>* friction_points = nullptr;
};

class SoftWideSolver {
 public:
  // Whether a world takes the float path this step.
  static bool Applies(const World& world, bool heavy_on_light) { return world.joints().empty() && !heavy_on_light; }
  // The sub-steps: the world's poses and `bodies` (v, w, dp, dR) at the
  // step's end, the points' impulses and totals as the double path leaves them.
  // The points and manifolds come without their rows and K^-1
  // (PrepareSoftPoints, BuildSoftManifolds), which the prepare kernel
  // computes in the bundles.
  void Run(const SoftWideStep& step, const std::vector<SoftManifold>& manifolds, const BlockColours& colours,
           ParallelRunner& runner, World& world, std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies);
  // The last step's friction rows (Jacobians, responses, masses), which
  // Run computes in float only, into `points`, for restitution after the
  // step (soft_restitution.h), which runs in the few steps with an impact.
  void UnpackFrictionRows(std::vector<SoftPoint>& points) const { bundles_.UnpackFrictionRows(points); }

 private:
  WideBodies bodies_;
  WideBundles bundles_;
  std::vector<ParallelRunner::Stage> stages_;
};

}  // namespace contactsim
