// The mimics' coupling rows (joint_rows.h, CouplingRow) solved together
// with the joint rows, by the Schur complement of the joints' block.
//
// With A = J M^-1 J^T + R the joints' system (its compliant rows' cfm in
// R) and B = J M^-1 J_c^T, D = J_c M^-1 J_c^T, the joint and coupling
// impulses (lambda, mu) of the bordered system
//   [A   B] [lambda]   [b  ]
//   [B^T D] [mu    ] = [b_c]
// follow from the joints' solution lambda_0 = A^-1 b (which the bodies
// already carry) and
//   S mu = b_c - B^T lambda_0,   S = D - B^T A^-1 B,   lambda = lambda_0 - A^-1 B mu
// (Golub and Van Loan, "Matrix Computations", 4th ed., section 3.2.11 on
// block elimination). Column c of S is measured rather than assembled: a
// unit impulse along coupling c, then the joints' solve that cancels what it
// did to their rows, and the coupling rows' velocities that remain. So
// every joint solver (tree, dense, a factor kept for the step) serves
// unchanged, a coupling costs one more joint solve per solve, and the
// joint rows hold exactly as before while the couplings hold too. A mimic
// is a handful of rows at most, so S is tiny and solved densely.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "service/contact/joints/joint_rows.h"

namespace contactsim {

// lambda = A^-1 b for the joint rows (the rows a solver keeps; 0 for the
// others).
using JointRowsSolve = std::function<Eigen::VectorXd(const Eigen::VectorXd& b)>;

// Given `bodies` whose velocities meet the joint rows that `solve` keeps,
// applies the coupling impulses mu and the joint impulses d_lambda that
// keep those rows met, so that every coupling row reaches J_c v = target_c.
// Returns the largest |target_c - J_c v| before (m/s or rad/s).
double SolveCouplings(const std::vector<ConstraintRow>& rows, const std::vector<CouplingRow>& couplings,
                      const Eigen::VectorXd& target, const JointRowsSolve& solve, std::vector<SolverBody>& bodies,
                      Eigen::VectorXd* d_lambda, Eigen::VectorXd* mu);

}  // namespace contactsim
