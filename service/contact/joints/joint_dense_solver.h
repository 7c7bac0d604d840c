// The dense solve of the joint system
//   (J M^-1 J^T + R) lambda = b,   R = kJointRegularisation diag(J M^-1 J^T)
// (joint_rows.h): the matrix is assembled from the rows that share a body
// and factored by Eigen's LDLT (robust Cholesky with pivoting; the matrix is
// symmetric positive definite once regularised). O(n^3) in the number of
// rows: the reference the tree solver is checked against, and the fallback
// for joint systems with loops.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/constraint_row.h"

namespace contactsim {

// J M^-1 J^T + R for the rows (n x n).
Eigen::MatrixXd JointSystemMatrix(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies);

// Solves the regularised system for lambda (one entry per row).
Eigen::VectorXd SolveJointsDense(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                                 const Eigen::VectorXd& b);

}  // namespace contactsim
