// Lemke's complementary pivoting method for LCP(M, q) (Lemke 1965; Cottle,
// Pang and Stone 1992, section 4.4; Murty, "Linear Complementarity, Linear
// and Nonlinear Programming", 1988, chapter 2).
//
// An artificial variable z0 with a covering vector d > 0 makes
//   w - M z - d z0 = q
// feasible at z = 0, z0 = -min_i q_i / d_i. From there the method pivots
// along the almost-complementary path: the variable that enters is always
// the complement of the one that just left, the one that leaves is chosen by
// the minimum-ratio test. It stops when z0 leaves (a solution) or when the
// entering column has no positive entry (a secondary ray: for a
// copositive-plus M, e.g. positive semi-definite, the LCP is then
// infeasible). Degenerate ties in the ratio test are broken
// lexicographically on the rows of (B^-1 q, B^-1), which prevents cycling
// (Cottle, Pang and Stone, section 4.9); among rows tied on the ratio the
// row of z0 is preferred so that the path ends as early as possible.
//
// The final basis is polished: with S the basic z, M_SS z_S = -q_S is solved
// once more by LU, so that round-off accumulated over the pivots does not
// reach the answer.
//
// Dependent rows (the four coplanar corners of a face, whose M_SS has rank
// three) make M singular and the LCP's solutions a set: Lemke's path ends at
// one of its vertices, which loads some corners and not others. With
// `regularization` eps > 0 the pivots solve LCP(M + eps I, q) instead, whose
// matrix is positive definite where M is semi-definite, so its one solution
// lies near the least-norm solution of the set (Tikhonov; ODE's constraint
// force mixing serves the same end), every dependent corner in the basis;
// the polish then solves M_SS z_S = -q_S for the least-norm z_S by a
// complete orthogonal decomposition, which removes the eps bias, and is
// kept when its complementarity error on M is no larger.
//
// Cost: O(n^2) per pivot on the dense tableau, typically O(n) pivots: meant
// for small and medium problems (up to a few hundred variables).
#pragma once

#include "service/contact/lcp/lcp_problem.h"

namespace contactsim {

struct LemkeOptions {
  int max_pivots = 0;            // 0: 50 (n + 1)
  double pivot_tolerance = 1e-12;// relative to the largest |M_ij| (and 1): smaller entries count as zero
  // > 0: the pivots run on M + regularization I, and the final basis is
  // polished on M itself by a minimum-norm solve (see above)
  double regularization = 0.0;
};

// Solves LCP(M, q) with the covering vector d = (1, ..., 1). Fills z, w,
// the pivot count and the outcome; z and w are valid only when solved.
LcpSolution SolveLemke(const MatX& M, const VecX& q, const LemkeOptions& options = {});

}  // namespace contactsim
