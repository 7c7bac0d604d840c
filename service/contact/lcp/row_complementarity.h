// How far constraint rows are from complementarity at the bodies' current
// velocities: max_k of (lambda_k - lo_k) max(w_k, 0) + (hi_k - lambda_k)
// max(-w_k, 0) with w_k = J_k v - rhs_k, an infinite bound replaced by
// |lambda_k|, friction bounds +-mu lambda_n from the row's normal row (J;
// zero exactly at a solution, |lambda w| for a contact row). A row whose
// velocity violates its bound at lambda = 0 shows in the solver's residual
// instead.
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"

namespace contactsim {

double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies);

}  // namespace contactsim
