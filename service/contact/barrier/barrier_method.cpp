#include "service/contact/barrier/barrier_method.h"

#include <algorithm>

#include "service/contact/patch_torsion.h"


namespace contactsim {

Status BarrierMethod::SetParams(const ParamMap& params) {
  const Status refused = RefusePatchTorsion(Name(), params,
                                            "its friction acts at the closest points of its own pair search "
                                            "(barrier/pair_search.h), which has no contact patch");
  if (!refused.ok()) return refused;
  return BarrierParamTable().Parse(Name(), params, params_, &params_);
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
