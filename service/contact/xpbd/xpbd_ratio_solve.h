// xpbd's contacts where a heavy body meets a light one (docs/methods/xpbd.md;
// docs/physics.md, "Mass ratios").
//
// One Gauss-Seidel sweep moves a heavy body's share of the error by about
// m_light / m_heavy (Erleben, "Velocity-based shock propagation", 2007).
// Sub-steps keep a heavy body *resting* on a light one shallow
// (XpbdMethod::SubstepsFor), but not one *landing* on it: each sub-step the
// light body is pushed into the ground and back, and the heavy one keeps
// most of its speed, so a 9.8 kg sphere landing at 2.2 m/s on a 0.1 kg box
// drove the box 45 mm into the ground.
// So in each component of dynamic bodies joined by contacts whose heaviest
// body is at least `mass_ratio` times its lightest, after each sub-step's
// sweeps the component's normal rows are solved together, in positions, by
// the subspace solve (subspace_solve.h): the displacements dx that bring
// every point to the separation the sweep aimed at,
//   J dx + alpha~ lambda = d,   d = min(-s, max_push),   lambda >= 0,
// lambda the point's multiplier accumulated over the sub-step (so a push
// the sweep gave may be taken back, as the sweep itself does). Friction
// stays with the sweep (xpbd_patch_friction.h), and so do the points on
// jointed bodies (xpbd_articulation.h), which the solve's free bodies would
// move off their joints. Worlds without such a
// component are untouched bit for bit.
// The solve is linear in the displacements, and a light body squeezed
// between heavy ones can be asked to turn far within a sub-step, where the
// linearisation fails: in 2 of 150 mixed-mass random scenes the scene's
// energy rose 4% and 170%. So the solve is kept only where it does not
// raise the kinetic energy of the velocities the sub-step will derive
// (v~ + dx / h, XpbdMethod::DeriveVelocities) above what the sweep left;
// otherwise the sweep's answer stands for that sub-step. Stopping a heavy
// body that lands on a light one, what the solve is for, lowers it.
#pragma once

#include <utility>
#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/mass_ratio_select.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/subspace_solve.h"
#include "service/contact/xpbd/xpbd_contact.h"

namespace contactsim {

class XpbdRatioSolve {
 public:
  // Finds the points of components that reach `mass_ratio` (0: none).
  // `bodies` at the step's start give the masses and inverse inertias.
  void Prepare(double mass_ratio, const std::vector<SoftBody>& bodies, const std::vector<XpbdPoint>& points);
  bool active() const { return !selected_.empty(); }
  // After a sub-step's sweeps: the selected points' normal rows solved
  // together; the bodies are moved and the points' multipliers updated
  // (the velocity pass reports them), unless that would raise the energy
  // of the velocities the sub-step derives (see above). `predicted`: the
  // poses and velocities after the sub-step's prediction.
  void Solve(const XpbdSolve& solve, const std::vector<SoftBody>& bodies, const std::vector<XpbdPose>& predicted,
             World& world, std::vector<XpbdPoint>& points);

 private:
  // The kinetic energy of the solve's bodies at the velocities the
  // sub-step would derive from their poses now.
  double DerivedEnergy(const std::vector<SoftBody>& bodies, const std::vector<XpbdPose>& predicted, double h,
                       const World& world) const;

  SubspaceOptions options_;
  std::vector<std::pair<Vec3, Quat>> saved_poses_;  // the solve's bodies before it, per slot
  std::vector<int> selected_;      // point indices, ascending
  RatioSolveBodies slots_;
  std::vector<ConstraintRow> rows_;  // per selected point: its normal
  SubspaceSolver subspace_;
};

}  // namespace contactsim
