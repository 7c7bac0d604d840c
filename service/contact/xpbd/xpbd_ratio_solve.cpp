#include "service/contact/xpbd/xpbd_ratio_solve.h"

#include <algorithm>

namespace contactsim {

void XpbdRatioSolve::Prepare(double mass_ratio, const std::vector<SoftBody>& bodies,
                             const std::vector<XpbdPoint>& points) {
  selected_ = SelectMassRatioPoints(bodies, points, mass_ratio);
  // a jointed point's bodies move as their joints let them, which the
  // solve's free bodies do not (xpbd_articulation.h)
  selected_.erase(std::remove_if(selected_.begin(), selected_.end(), [&](int k) { return points[k].jointed; }),
                  selected_.end());
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

double XpbdRatioSolve::DerivedEnergy(const std::vector<SoftBody>& bodies, const std::vector<XpbdPose>& predicted,
                                     double h, const World& world) const {
  double energy = 0.0;
  for (int i : slots_.body_of_slot) {
    const RigidBody& b = world.bodies()[i];
    Quat dq = b.q * predicted[i].q.conjugate();
    if (dq.w() < 0.0) dq.coeffs() = -dq.coeffs();
    const Vec3 v = bodies[i].v + (b.x - predicted[i].x) / h;
    const Vec3 w = bodies[i].w + (2.0 / h) * dq.vec();
    energy += 0.5 * (b.mass * v.squaredNorm() + w.dot(bodies[i].inv_inertia.inverse() * w));
  }
  return energy;
}

void XpbdRatioSolve::Solve(const XpbdSolve& solve, const std::vector<SoftBody>& bodies,
                           const std::vector<XpbdPose>& predicted, World& world, std::vector<XpbdPoint>& points) {
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
    r.rhs = std::min(-XpbdSeparation(p, world) - XpbdSlack(p, solve.elapsed), solve.max_push);
    r.cfm = solve.alpha_tilde;
    r.lo = 0.0;
  }
  for (SolverBody& s : slots_.solver) s.v.setZero(), s.w.setZero(), s.dP.setZero(), s.dL.setZero();
  subspace_.Solve(rows_, slots_.solver, options_);
  auto& all = world.bodies();
  const double before = DerivedEnergy(bodies, predicted, solve.h, world);
  saved_poses_.clear();
  for (int i : slots_.body_of_slot) saved_poses_.emplace_back(all[i].x, all[i].q);
  for (size_t s = 0; s < slots_.body_of_slot.size(); ++s) {
    const int i = slots_.body_of_slot[s];
    DisplaceXpbdBody(all[i], bodies[i], slots_.solver[s].v, slots_.solver[s].w);
  }
  if (DerivedEnergy(bodies, predicted, solve.h, world) > before * (1.0 + 1e-6) + 1e-12) {
    for (size_t s = 0; s < slots_.body_of_slot.size(); ++s) {
      RigidBody& b = all[slots_.body_of_slot[s]];
      b.x = saved_poses_[s].first;
      b.q = saved_poses_[s].second;
    }
    return;
  }
  for (size_t i = 0; i < selected_.size(); ++i) {
    XpbdPoint& p = points[selected_[i]];
    p.lambda_n = rows_[i].lambda;
  }
}

}  // namespace contactsim
