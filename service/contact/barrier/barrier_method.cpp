#include "service/contact/barrier/barrier_method.h"

#include <algorithm>

#include "service/contact/param_reader.h"

namespace contactsim {

Status BarrierMethod::SetParams(const ParamMap& params) {
  BarrierParams p = params_;
  ParamReader r(Name(), params);
  r.Double("d_hat", 1e-6, 0.1, &p.d_hat);
  r.Double("kappa_ortho", 1e3, 1e15, &p.kappa_ortho);
  r.Double("eps_v", 1e-6, 1.0, &p.eps_v);
  r.Double("tolerance", 1e-9, 1.0, &p.tolerance);
  r.Int("max_iterations", 1, 1000, &p.max_iterations);
  r.Double("ccd_fraction", 0.01, 0.9, &p.ccd_fraction);
  Status status = r.Finish();
  if (status.ok()) params_ = p;
  return status;
}

ParamMap BarrierMethod::Params() const {
  return {{"d_hat", FormatValue(params_.d_hat)},
          {"kappa_ortho", FormatValue(params_.kappa_ortho)},
          {"eps_v", FormatValue(params_.eps_v)},
          {"tolerance", FormatValue(params_.tolerance)},
          {"max_iterations", std::to_string(params_.max_iterations)},
          {"ccd_fraction", FormatValue(params_.ccd_fraction)}};
}

Status BarrierMethod::LoadState(const std::string& bytes) {
  if (!solver_.mutable_state().Restore(bytes)) {
    return Status::InvalidArgument("barrier method state: " + std::to_string(bytes.size()) +
                                   " bytes are not a saved affine state and friction lag");
  }
  return Status::Ok();
}

StepStats BarrierMethod::Step(World& world, CollisionDetector& /*detector*/, ContactSet* contacts) {
  world.AccumulateForces();
  last_ = solver_.Step(world, params_, contacts);
  world.FinishStep();
  StepStats stats;
  stats.iterations = last_.iterations;
  stats.substeps = last_.converged ? 1 : 0;
  stats.residual = last_.min_distance;
  stats.stiffness = last_.kappa;
  stats.contacts = static_cast<int>(contacts->size());
  stats.max_penetration = std::max(0.0, -last_.min_distance);
  return stats;
}

}  // namespace contactsim
