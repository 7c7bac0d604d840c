// The mixed LCP of joints and contacts: rows F are equalities (bilateral
// joint rows, w_F = 0 with x_F free), rows C are complementary
// (w_C >= 0, x_C >= 0, x_C . w_C = 0), all in
//   w = A x + b.
// The free rows are eliminated by their Schur complement (Cottle, Pang and
// Stone 1992, section 2.3; Murty 1988, section 1.2):
//   x_F = -A_FF^+ (A_FC x_C + b_F),
//   M = A_CC - A_CF A_FF^+ A_FC,   q = b_C - A_CF A_FF^+ b_F,
// and LCP(M, q) goes to Lemke. A_FF^+ is the complete orthogonal
// (minimum-norm) solve, so that redundant joint rows (a singular A_FF, e.g.
// a closed loop) still give an answer.
#pragma once

#include <vector>

#include "service/contact/lcp/lemke.h"

namespace contactsim {

// free[i] marks row i as an equality. Returns x (all rows) in z and w = A x + b.
LcpSolution SolveMixedLcp(const MatX& A, const VecX& b, const std::vector<bool>& free,
                          const LemkeOptions& options = {});

}  // namespace contactsim
