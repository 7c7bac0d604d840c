// The linearly implicit momentum step of the penalty method, after Xu, Zhao
// and Barbic, "Implicit multibody penalty-based distributed contact", IEEE
// TVCG 20(9), 2014: the contact forces are linearised in positions (stiffness
// K = df/dx) and velocities (damping D = df/du), and one linear system per
// step gives the new velocities, so stiff contacts stay stable at a time
// step where the explicit step diverges.
//
// Generalised velocities u = (v, w) per body, M = diag(m 1, I_world). With
// positions moving by dx = h ((1 - theta) u0 + theta u1) and forces taken at
// the same theta point, f(theta) = f0 + theta (K dx + D du), du = u1 - u0:
//   (M - theta h D - theta^2 h^2 K) du = h (f0 + theta h K u0).
// theta = 1 is the classic (M - h D - h^2 K) du = h (f + h K u) (linearly
// implicit Euler: L-stable, damps stiff modes, and damps a bounce too);
// theta = 1/2 is the trapezoidal rule (no numerical damping of a linear
// spring, so restitution is reproduced, but stiff modes are not damped).
//
// Per contact point with normal Jacobian G (vn = G u) the normal force is
//   lambda(theta) = lambda0 - theta k h vn0 - theta (theta k h + c) G du,
// k = d lambda / d depth, c = -d lambda / d vn (penalty_force.h), which adds
// h theta (theta k h + c) G^T G to the matrix (symmetric, positive: the
// system stays solvable for any kp). A sticking friction point adds the same
// with kt, ct for the two tangents T; a sliding point's force mu lambda s
// along a fixed direction s adds h mu theta (theta k h + c) S^T G
// (unsymmetric, hence LU). The normal direction is held fixed over the step
// (the geometric stiffness of a turning normal is left out).
//
// Complementarity by active sets: a point whose lambda(theta) comes out
// negative is switched off (no pull), a predicted point whose lambda comes
// out positive is switched on, a sticking point outside mu lambda slides, a
// sliding point whose slip reverses sticks, and the system is solved again,
// up to `max_iterations` passes.
//
// One system per contact island (bodies connected through dynamic-dynamic
// contacts), 6 unknowns per body, sparse (a 6 x 6 block per body and per
// touching pair) and solved by sparse LU with COLAMD ordering (Eigen's
// SparseLU; the sliding rows make it unsymmetric). The dense LU this
// replaced took 1.2 s per step on a 1,000-sphere pile, one island of 6,000
// unknowns.
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_row.h"

namespace contactsim {

struct ImplicitStats {
  int iterations = 0;     // active-set passes, summed over the islands
  double residual = 0.0;  // N: largest complementarity violation left (negative lambda, friction outside the disk)
};

// Advances P and L of every dynamic body by h: bodies in a contact island by
// the implicit solve, the others by P += F h, L += tau h. Writes lambda, ft
// and sliding of every engaged row.
ImplicitStats ImplicitMomentumStep(World& world, std::vector<PenaltyRow>& rows, double h, double theta,
                                   int max_iterations);

}  // namespace contactsim
