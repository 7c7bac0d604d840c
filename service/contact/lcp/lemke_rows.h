// Constraint rows solved exactly as one mixed LCP by Lemke's method: the
// velocity-level time-stepping problem of Stewart and Trinkle ("An implicit
// time-stepping scheme for rigid body dynamics with inelastic collisions
// and Coulomb friction", IJNME 1996) and Anitescu and Potra ("Formulating
// dynamic multi-rigid-body contact problems with friction as solvable
// linear complementarity problems", Nonlinear Dynamics 1997), with joints
// as equality rows.
//
// With G = J M^-1 J^T (+ the rows' cfm on its diagonal) and c = J v* - rhs (v* the velocities before the
// solve) each row becomes:
//   equality (lo = -inf, hi = +inf):  G_k lambda + c_k = 0, lambda_k free;
//   unilateral (lo = 0, hi = +inf):   0 <= lambda_k  _|_  G_k lambda + c_k >= 0;
//   upper limit (lo = -inf, hi = 0):  0 <= -lambda_k _|_  -(G_k lambda + c_k) >= 0;
//   friction (normal_row n, |lambda_k| <= mu lambda_n), lambda_k = b+ - b-
//   with a slip-speed variable g (Stewart-Trinkle with the directions +-t_k):
//     0 <= b+  _|_  u_k + g >= 0,    0 <= b-  _|_  -u_k + g >= 0,
//     0 <= g   _|_  mu lambda_n - b+ - b- >= 0,   u_k = G_k lambda + c_k.
// Each tangent row is its own 1D Coulomb law, so the friction set is the
// box |lambda_t1|, |lambda_t2| <= mu lambda_n, a four-sided pyramid inside
// which the Coulomb disk is inscribed: exact along t1 and t2, up to
// sqrt(2) mu lambda_n between them. The lcp method therefore builds Lemke's
// friction rows with t1 along each contact's predicted slip
// (lcp_contact_rows.h), where the bound is exact; PGS projects onto the
// disk itself (pgs.h). Anitescu and Potra show that Lemke's method
// processes these LCPs (their matrix is copositive-plus after the
// substitution), so ray termination means a modelling error, reported.
//   box (lo = -hi, 0 < hi < inf: a joint's friction): the friction form
//     with the fixed bound hi in place of mu lambda_n.
// A compliant row (cfm > 0, a joint's damping) adds cfm to G_kk.
// Other bounds are not expressed here: InvalidArgument.
// Friction rows must name a [0, inf) normal row.
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/lcp/lemke.h"
#include "service/contact/lcp/solve_report.h"
#include "service/physics/status.h"

namespace contactsim {

// The regularisation the lcp method's Lemke runs with (LemkeOptions, on the
// unit-diagonal tableau below): 1e-9 gives every corner of a face its share
// (six touching cubes struck at 5 m/s leave 1.8e-12 v0 off the analytic
// answer, 0.035 v0 without; a gripped box slips 3e-17 m in 2 s, 7 mm
// without), 1e-12 left round-off to choose (0.013 v0 before the polish),
// and the polish removes its bias from the answer.
constexpr double kLemkeRegularization = 1e-9;

// On success rows' lambda hold the impulses and the bodies have received
// them; on a Lemke failure (report->outcome) nothing is applied.
Status SolveRowsLemke(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                      const LemkeOptions& options, SolveReport* report);

}  // namespace contactsim
