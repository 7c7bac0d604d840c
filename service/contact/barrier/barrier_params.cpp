#include "service/contact/barrier/barrier_params.h"

namespace contactsim {

const ParamTable<BarrierParams>& BarrierParamTable() {
  using P = BarrierParams;
  static const ParamTable<P> table = {
      DoubleParam("d_hat", &P::d_hat, 1e-6, 0.1, "m", "activation distance of the barrier"),
      DoubleParam("kappa_ortho", &P::kappa_ortho, 1e3, 1e15, "Pa",
                  "orthogonality stiffness of the affine bodies (times the body's volume)"),
      DoubleParam("ortho_step_ratio", &P::ortho_step_ratio, 0.0, 1e15, "",
                  "largest h^2 k / lambda_max(S) of a body's orthogonality stiffness k, its affine inertia S; "
                  "kappa_ortho vol is capped there (0 = no cap)"),
      DoubleParam("eps_v", &P::eps_v, 1e-6, 1.0, "m/s",
                  "friction's static-to-dynamic slip speed; static friction creeps slower than this"),
      DoubleParam("tolerance", &P::tolerance, 1e-9, 1.0, "m/s", "Newton stops when every vertex moves slower"),
      IntParam("max_iterations", &P::max_iterations, 1, 1000, "", "Newton iterations per step at most"),
      DoubleParam("ccd_fraction", &P::ccd_fraction, 0.01, 0.9, "",
                  "a line-search step keeps each distance above this fraction of its start"),
      IntParam("friction_lag_passes", &P::friction_lag_passes, 1, 100, "",
               "minimisations a step at most, each with friction lagged at the last one's solution"),
      DoubleParam("friction_lag_tolerance", &P::friction_lag_tolerance, 0.0, 1.0, "",
                  "the lag has settled when no pair's mu lambda moves by more than this fraction of the largest"),
  };
  return table;
}

}  // namespace contactsim
