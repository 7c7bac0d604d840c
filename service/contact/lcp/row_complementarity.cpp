#include "service/contact/lcp/row_complementarity.h"

#include <algorithm>
#include <cmath>

namespace contactsim {

double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies) {
  double err = 0.0;
  for (const ConstraintRow& r : rows) {
    const double w = r.Velocity(bodies) - r.rhs;
    double lo = r.lo, hi = r.hi;
    if (r.normal_row >= 0) {
      hi = r.mu * rows[r.normal_row].lambda;
      lo = -hi;
    }
    const double to_lo = std::isfinite(lo) ? r.lambda - lo : std::abs(r.lambda);
    const double to_hi = std::isfinite(hi) ? hi - r.lambda : std::abs(r.lambda);
    err = std::max(err, to_lo * std::max(w, 0.0) + to_hi * std::max(-w, 0.0));
  }
  return err;
}

}  // namespace contactsim
