// The Delassus matrix of a set of constraint rows, G = J M^-1 J^T (dense),
// and the row velocities J v: the LCP matrix of velocity-level time
// stepping (Stewart and Trinkle 1996) and, for contact normals, Baraff's
// matrix A of resting contact (Baraff 1994: a_ij is the normal acceleration
// at contact i per unit normal force at contact j, which is the same
// entry).
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/lcp/lcp_problem.h"

namespace contactsim {

// Only pairs of rows that share a body with mass are visited (the matrix is
// block sparse), in O(sum over bodies of rows^2).
MatX DenseDelassus(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies);

// J_k v for every row at the bodies' current velocities.
VecX RowVelocities(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies);

}  // namespace contactsim
