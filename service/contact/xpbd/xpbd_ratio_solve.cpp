#include "service/contact/xpbd/xpbd_ratio_solve.h"

#include <algorithm>

namespace contactsim {

void XpbdRatioSolve::Prepare(double mass_ratio, const std::vector<SoftBody>& bodies,
                             const std::vector<XpbdPoint>& points) {
  selected_ = SelectMassRatioPoints(bodies, points, mass_ratio);
  if (selected_.empty()) return;
  slots_.Build(bodies, points, selected_);
  options_ = SubspaceOptions{};
  options_.mass_ratio = mass_ratio;
  // every row free at first and held one a pass, as in the soft step
  // (soft_stages.cpp), whose single sweep leaves as rough an active set
  options_.start_free = true;
  options_.passes = 16;
  options_.energy_guard = false;  // displacements, not velocities
}

void XpbdRatioSolve::Solve(const XpbdSolve& solve, const std::vector<SoftBody>& bodies, World& world,
                           std::vector<XpbdPoint>& points) {
  rows_.resize(selected_.size());
  for (size_t i = 0; i < selected_.size(); ++i) {
    const XpbdPoint& p = points[selected_[i]];
    ConstraintRow& r = rows_[i];
    r = ConstraintRow{};
    r.a = slots_.slot_of_body[p.a];
    r.b = slots_.slot_of_body[p.b];
    r.lin_a = -p.n, r.ang_a = -p.ra_n;
    r.lin_b = p.n, r.ang_b = p.rb_n;
    r.lambda = p.lambda_n;
    r.rhs = std::min(-XpbdSeparation(p, world), solve.max_push);
    r.cfm = solve.alpha_tilde;
    r.lo = 0.0;
  }
  for (SolverBody& s : slots_.solver) s.v.setZero(), s.w.setZero(), s.dP.setZero(), s.dL.setZero();
  subspace_.Solve(rows_, slots_.solver, options_);
  auto& all = world.bodies();
  for (size_t s = 0; s < slots_.body_of_slot.size(); ++s) {
    const int i = slots_.body_of_slot[s];
    DisplaceXpbdBody(all[i], bodies[i], slots_.solver[s].v, slots_.solver[s].w);
  }
  for (size_t i = 0; i < selected_.size(); ++i) {
    XpbdPoint& p = points[selected_[i]];
    const double dl = rows_[i].lambda - p.lambda_n;
    p.lambda_n = rows_[i].lambda;
    p.impulse += (dl * solve.inv_h) * p.n;
  }
}

}  // namespace contactsim
