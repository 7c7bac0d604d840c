// The barrier method: intersection-free contact by Incremental Potential
// Contact (Li et al. 2020) on affine bodies (Lan et al. 2022); the step is
// barrier_solver.h. StepStats: iterations = Newton iterations, residual =
// the smallest distance (m) between two bodies' primitives within d_hat at
// the end of the step (d_hat when none is nearer), converged or not in
// substeps (1) / 0, stiffness = the barrier stiffness kappa (N/m), also
// barrier_stiffness(). Contacts
// are the primitive pairs within d_hat, with depth = -distance and the
// barrier force kappa |b'(d)| (N) as normal_value (ValueKind kForce).
#pragma once

#include "service/contact/barrier/barrier_solver.h"
#include "service/contact/contact_method.h"

namespace contactsim {

class BarrierMethod : public ContactMethod {
 public:
  const char* Name() const override { return "barrier"; }
  ContactValueKind ValueKind() const override { return ContactValueKind::kForce; }
  Status SetParams(const ParamMap& params) override;
  ParamMap Params() const override { return BarrierParamTable().ToMap(params_); }
  std::vector<ParamDoc> ParamDocs() const override { return BarrierParamTable().Docs(); }
  StepStats Step(World& world, CollisionDetector& detector, ContactSet* contacts) override;
  // The affine state and lagged friction (barrier_state.h) are the caches.
  void ResetCaches() override { solver_.mutable_state().Clear(); }
  std::string SaveState() const override { return solver_.state().Save(); }
  Status LoadState(const std::string& bytes) override;
  const BarrierParams& params() const { return params_; }
  // N/m, the barrier stiffness kappa of the last step
  double barrier_stiffness() const { return last_.kappa; }
  const BarrierStepResult& last_step() const { return last_; }

 private:
  BarrierParams params_;
  BarrierSolver solver_;
  BarrierStepResult last_;
};

}  // namespace contactsim
