// Parameters of the barrier method (barrier_method.h, barrier_solver.h):
// the struct holds the defaults; each one's range, unit and meaning are
// declared once, in BarrierParamTable() (barrier_params.cpp; param_table.h).
#pragma once

#include "service/contact/param_table.h"

namespace contactsim {

struct BarrierParams {
  double d_hat = 1e-3;          // m
  double kappa_ortho = 1e10;    // Pa
  // The largest h^2 k / lambda_max(S) a body's orthogonality stiffness k
  // may reach (S its affine inertia, affine_body.h): kappa_ortho vol is
  // capped there. The ratio is the square of the stiff mode's frequency
  // times the step; above a few 1e4 Newton needs ever more iterations to
  // turn a body (a 0.1 kg plate at 100 rad/s: 4e5, 100 iterations a step),
  // while a light body's strain under the cap, (h w)^2 / ratio at spin w,
  // stays below 1e-5 (docs/methods/barrier.md, "Light bodies")
  double ortho_step_ratio = 2e4;
  // m/s. Below it the smoothed
  // friction of IPC sec. 5 is a stiff viscous force, so a contact that
  // static friction holds with a fraction r < 1 of mu lambda still slips at
  // eps_v (1 - sqrt(1 - r)) < eps_v (f1(y) = r, barrier_potential.h): the
  // creep bound. 1e-4 m/s, the Newton tolerance: IPC's 1e-3 m/s let a box
  // held on a 30 degree slope with mu 0.7 creep 1.1 mm in 2 s; smaller
  // values than the tolerance are below what Newton resolves and cost
  // convergence (a 32-sphere pile: 0, 53 and 120 of 240 steps at the
  // iteration cap with 1e-3, 1e-4 and 1e-5 m/s)
  double eps_v = 1e-4;
  double tolerance = 1e-4;      // m/s
  int max_iterations = 50;
  double ccd_fraction = 0.1;
  // IPC's lagged iterations (sec. 5): a step's minimisation is repeated
  // from its solution with the friction lagged there, at most
  // friction_lag_passes times in all, until no pair of bodies' lagged
  // mu lambda moves by more than friction_lag_tolerance of the largest.
  // Lagged once from the step's start, the normal forces of a cube rocking
  // as it slides trail a step behind, and a cube launched along the ground
  // stops 1.8% short, 0.83% with the lag converged (3 passes); the repeats
  // cost the settling pyramid 2.6 times its Newton iterations, so one pass
  // is the default (docs/methods/barrier.md, "Lagged iterations")
  int friction_lag_passes = 1;
  double friction_lag_tolerance = 1e-3;
};

const ParamTable<BarrierParams>& BarrierParamTable();

}  // namespace contactsim
