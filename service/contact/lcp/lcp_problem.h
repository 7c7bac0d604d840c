// A dense linear complementarity problem LCP(M, q): find z such that
//   w = M z + q,  w >= 0,  z >= 0,  z . w = 0
// (Cottle, Pang and Stone, "The Linear Complementarity Problem", 1992).
// Resting contact (Baraff 1994) and velocity-level time stepping
// (Stewart and Trinkle 1996; Anitescu and Potra 1997) both reduce to it.
#pragma once

#include <Eigen/Core>

namespace contactsim {

using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

enum class LcpOutcome {
  kSolved,
  kRayTermination,  // Lemke left on an unbounded ray: no solution found (infeasible or M not copositive-plus)
  kPivotLimit,      // gave up after the pivot cap
  kSingular,        // a Schur complement or a basis was singular
};

const char* LcpOutcomeName(LcpOutcome outcome);

struct LcpSolution {
  VecX z, w;
  LcpOutcome outcome = LcpOutcome::kSolved;
  int pivots = 0;
};

// Largest violation of the LCP conditions by z: max of -z_i, -w_i and
// |z_i w_i| with w = M z + q (0 for an exact solution).
double LcpError(const MatX& M, const VecX& q, const VecX& z);

}  // namespace contactsim
