// How far constraint rows are from complementarity at the bodies' current
// velocities (J; zero exactly at a solution), with w_k = J_k v - rhs_k:
//   * a scalar row: (lambda_k - lo_k) max(w_k, 0) + (hi_k - lambda_k)
//     max(-w_k, 0), an infinite bound replaced by |lambda_k|, |lambda w|
//     for a contact row;
//   * a friction pair (friction_disk.h) under FrictionSet::kDisk: the
//     disk's gap mu lambda_n |u| + lambda_t . u (DiskComplementarity);
//     under kPyramid each friction row alone, with bounds +-mu lambda_n.
// The maximum over the rows. A row whose velocity violates its bound at
// lambda = 0 shows in the solver's residual instead.
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"

namespace contactsim {

// The set the tangential impulses of a friction pair are bounded by: PGS
// projects onto the disk, Lemke's rows express the pyramid (lemke_rows.h).
enum class FrictionSet { kDisk, kPyramid };

double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                            FrictionSet set = FrictionSet::kDisk);
// The maximum over rows [begin, end) (a friction pair counts where its
// lead is), so that the ranges of a split give the whole's maximum.
double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                            FrictionSet set, size_t begin, size_t end);

}  // namespace contactsim
