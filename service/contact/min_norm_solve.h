// The minimum-norm solution of S y = b for a sparse symmetric positive
// semidefinite S with unit diagonal: the Jacobi-scaled Delassus matrix of
// a direct solve (subspace_solve.h), singular wherever coplanar contact
// points share a face (four normal rows, rank three) or statically
// indeterminate supports share a body.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace contactsim {

struct MinNormReport {
  bool fallback = false;  // the dense decomposition answered (b outside S's range)
};

// First the sparse Cholesky factor of S + eps I (Tikhonov regularisation:
// its solution tends to the minimum-norm one as eps -> 0 and leaves S's
// null space alone when b lies in S's range), with two steps of iterative
// refinement against S itself, which remove the eps / sigma bias along the
// directions S acts on (Golub and Van Loan, "Matrix Computations", 3.5.3).
// A stack's matrix is banded, so this costs about as much as a few sweeps.
// When the residual shows that b has a part outside S's range (targets no
// impulses can meet, such as coplanar points asked for speeds no rigid
// motion gives), a dense complete orthogonal decomposition gives the
// least-squares minimum-norm answer instead.
Eigen::VectorXd MinNormSolve(const Eigen::SparseMatrix<double>& S, const Eigen::VectorXd& b,
                             MinNormReport* report = nullptr);

}  // namespace contactsim
