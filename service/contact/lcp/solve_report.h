// What a row solver (PGS or Lemke on rows) reports for one solve.
#pragma once

#include "service/contact/lcp/lcp_problem.h"

namespace contactsim {

struct SolveReport {
  int iterations = 0;             // PGS sweeps, or Lemke pivots
  double residual = 0.0;          // m/s: PGS, last sweep's largest row-velocity change; Lemke, largest LCP violation
  double complementarity = 0.0;   // J: ComplementarityError after the solve (row_complementarity.h)
  bool converged = false;         // PGS: residual below tolerance; Lemke: solved
  LcpOutcome outcome = LcpOutcome::kSolved;  // Lemke only
};

}  // namespace contactsim
