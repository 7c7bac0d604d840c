// One scalar velocity constraint between two bodies, the common currency of
// the constraint solvers (joints, the LCP method's contact and friction rows).
//
// The row's Jacobian J acts on the stacked velocities of its two bodies:
//   J qdot = lin_a . v_a + ang_a . w_a + lin_b . v_b + ang_b . w_b,
// and an impulse lambda along the row adds J^T lambda to their momenta
// (P += lin lambda, L += ang lambda). A solver looks for lambda in [lo, hi]
// such that J qdot_new = rhs (equality rows: lo = -inf, hi = +inf) or the
// complementarity conditions hold at the bounds (Cottle, Pang and Stone,
// "The Linear Complementarity Problem", 1992; Erleben 2013 for the boxed
// form used by projected Gauss-Seidel).
#pragma once

#include <limits>
#include <vector>

#include "service/contact/solver_body.h"

namespace contactsim {

struct ConstraintRow {
  static constexpr double kInf = std::numeric_limits<double>::infinity();

  int a = -1, b = -1;                  // solver body indices; -1: the world
  Vec3 lin_a = Vec3::Zero(), ang_a = Vec3::Zero();
  Vec3 lin_b = Vec3::Zero(), ang_b = Vec3::Zero();
  double rhs = 0.0;                    // m/s or rad/s: target of J qdot
  double lo = -kInf, hi = kInf;        // N s (or N m s): impulse bounds
  // Friction rows: the bounds are -mu lambda_n .. +mu lambda_n of the normal
  // row at index `normal_row` of the same row list (-1: fixed bounds).
  int normal_row = -1;
  double mu = 0.0;
  double lambda = 0.0;                 // accumulated impulse (warm start in, result out)
  // Compliance of a soft row (s/kg): it aims at J qdot + cfm lambda = rhs,
  // a spring whose give grows with the impulse it carries (softness.h). The
  // soft step's rows set it; every other solver's rows are rigid (0).
  double cfm = 0.0;

  double Velocity(const std::vector<SolverBody>& s) const {
    double jv = 0.0;
    if (a >= 0) jv += lin_a.dot(s[a].v) + ang_a.dot(s[a].w);
    if (b >= 0) jv += lin_b.dot(s[b].v) + ang_b.dot(s[b].w);
    return jv;
  }
  // J M^-1 J^T for this row alone (the diagonal entry of the Delassus matrix).
  double Diagonal(const std::vector<SolverBody>& s) const {
    double d = 0.0;
    if (a >= 0) d += s[a].inv_mass * lin_a.squaredNorm() + ang_a.dot(s[a].inv_inertia * ang_a);
    if (b >= 0) d += s[b].inv_mass * lin_b.squaredNorm() + ang_b.dot(s[b].inv_inertia * ang_b);
    return d;
  }
  // Adds J^T d_lambda to the bodies (through SolverBody, so dP and dL sum).
  void Apply(double d_lambda, std::vector<SolverBody>& s) const {
    if (a >= 0) ApplyTo(s[a], lin_a * d_lambda, ang_a * d_lambda);
    if (b >= 0) ApplyTo(s[b], lin_b * d_lambda, ang_b * d_lambda);
  }

 private:
  static void ApplyTo(SolverBody& body, const Vec3& dp, const Vec3& dl) {
    if (body.inv_mass == 0.0) return;
    body.v += body.inv_mass * dp;
    body.w += body.inv_inertia * dl;
    body.dP += dp;
    body.dL += dl;
  }
};

}  // namespace contactsim
