// The Coulomb friction disk of a contact's two friction rows, shared by the
// row solvers and their complementarity measure.
//
// Coulomb's law bounds the tangential impulse lambda_t = (lambda_t1,
// lambda_t2) by the disk |lambda_t| <= mu lambda_n, whatever the direction;
// the box |lambda_t1|, |lambda_t2| <= mu lambda_n of two independent 1D
// laws (a four-sided pyramid) lets sliding along the diagonal of t1 and t2
// feel up to sqrt(2) mu lambda_n. Two consecutive rows naming the same
// normal row (lcp_contact_rows.h appends normal, t1, t2) are one friction
// pair and are treated as one 2D law.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "service/contact/constraint_row.h"

namespace contactsim {

// Row k is the first row of a friction pair: it and row k + 1 are friction
// rows of the same normal row, and row k - 1 is not one of them.
inline bool IsFrictionPairLead(const std::vector<ConstraintRow>& rows, size_t k) {
  const int n = rows[k].normal_row;
  return n >= 0 && k + 1 < rows.size() && rows[k + 1].normal_row == n && (k == 0 || rows[k - 1].normal_row != n);
}

// Row k is the second row of a friction pair.
inline bool IsFrictionPairSecond(const std::vector<ConstraintRow>& rows, size_t k) {
  return k > 0 && IsFrictionPairLead(rows, k - 1);
}

// The nearest point of the disk of radius `radius` (>= 0) to (x, y),
// in place: a radial scaling when outside.
inline void ProjectOntoDisk(double radius, double* x, double* y) {
  const double r2 = *x * *x + *y * *y;
  if (r2 <= radius * radius) return;
  const double s = radius / std::sqrt(r2);
  *x *= s;
  *y *= s;
}

// The complementarity error of one friction pair (J): with u the pair's
// slip velocity (w_t1, w_t2), the Fenchel-Young gap of the disk,
//   mu lambda_n |u| + lambda_t . u >= 0,
// zero exactly when the pair sticks (u = 0) or slides with the full
// lambda_t = -mu lambda_n u / |u| (maximal dissipation, Moreau 1988).
inline double DiskComplementarity(double mu_lambda_n, double l1, double l2, double u1, double u2) {
  return std::max(0.0, mu_lambda_n * std::sqrt(u1 * u1 + u2 * u2) + l1 * u1 + l2 * u2);
}

}  // namespace contactsim
