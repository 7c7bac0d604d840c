#include "service/contact/joints/joint_couplings.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace contactsim {

double SolveCouplings(const std::vector<ConstraintRow>& rows, const std::vector<CouplingRow>& couplings,
                      const Eigen::VectorXd& target, const JointRowsSolve& solve, std::vector<SolverBody>& bodies,
                      Eigen::VectorXd* d_lambda, Eigen::VectorXd* mu) {
  const int n = static_cast<int>(rows.size());
  const int nc = static_cast<int>(couplings.size());
  *d_lambda = Eigen::VectorXd::Zero(n);
  *mu = Eigen::VectorXd::Zero(nc);
  if (nc == 0) return 0.0;
  // the response to a unit impulse along each coupling, with the joints'
  // answer to it: column c of S and of -A^-1 B
  std::vector<SolverBody> response = bodies;
  Eigen::MatrixXd S(nc, nc), L(n, nc);
  Eigen::VectorXd b(n);
  for (int c = 0; c < nc; ++c) {
    for (SolverBody& s : response) s.v.setZero(), s.w.setZero();
    couplings[c].Apply(1.0, response);
    for (int k = 0; k < n; ++k) b[k] = -rows[k].Velocity(response);
    L.col(c) = n > 0 ? solve(b) : Eigen::VectorXd();
    for (int k = 0; k < n; ++k) rows[k].Apply(L(k, c), response);
    for (int d = 0; d < nc; ++d) S(d, c) = couplings[d].Velocity(response);
  }
  Eigen::VectorXd r(nc);
  double worst = 0.0;
  for (int c = 0; c < nc; ++c) {
    r[c] = target[c] - couplings[c].Velocity(bodies);
    worst = std::max(worst, std::abs(r[c]));
  }
  // the joints' regularisation (joint_rows.h): a coupling that the joints
  // already fix (both coordinates at a limit) still gets a bounded answer
  for (int c = 0; c < nc; ++c) S(c, c) *= 1.0 + kJointRegularisation;
  *mu = S.ldlt().solve(r);
  *d_lambda = L * *mu;
  for (int c = 0; c < nc; ++c) couplings[c].Apply((*mu)[c], bodies);
  for (int k = 0; k < n; ++k) rows[k].Apply((*d_lambda)[k], bodies);
  return worst;
}

}  // namespace contactsim
