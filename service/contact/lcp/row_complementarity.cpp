#include "service/contact/lcp/row_complementarity.h"

#include <algorithm>
#include <cmath>

#include "service/contact/lcp/friction_disk.h"

namespace contactsim {

double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                            FrictionSet set) {
  return ComplementarityError(rows, bodies, set, 0, rows.size());
}

double ComplementarityError(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                            FrictionSet set, size_t begin, size_t end) {
  double err = 0.0;
  for (size_t k = begin; k < end; ++k) {
    const ConstraintRow& r = rows[k];
    const double w = r.Velocity(bodies) - r.rhs;
    if (set == FrictionSet::kDisk && IsFrictionPairSecond(rows, k)) continue;  // measured with its lead
    if (set == FrictionSet::kDisk && IsFrictionPairLead(rows, k)) {
      const ConstraintRow& s = rows[k + 1];
      const double w2 = s.Velocity(bodies) - s.rhs;
      err = std::max(err, DiskComplementarity(r.mu * rows[r.normal_row].lambda, r.lambda, s.lambda, w, w2));
      continue;
    }
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
