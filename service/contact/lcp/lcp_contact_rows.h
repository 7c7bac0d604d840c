// Contacts as constraint rows for the velocity-level LCP (Stewart and
// Trinkle 1996; Anitescu and Potra 1997): per contact one normal row and
// two friction rows along the tangents t1, t2 of contact_row.h (a basis that
// depends only on n, so that it is the same from step to step).
//
// Normal row, J v = n . (v_B(p) - v_A(p)) = vn, lambda in [0, inf):
//   * colliding (vn- < -restitution_threshold, vn- the approach speed at the
//     step's start, before forces): rhs = -e vn- (Newton's law of
//     restitution at the velocity level);
//   * a gap (depth < 0, a speculative contact within the slop):
//     rhs = depth / h, the bodies may close the gap in this step, no more;
//   * otherwise rhs = 0, plus erp (depth - slop) / h with drift = baumgarte
//     (Baumgarte stabilisation: it turns penetration into separating
//     velocity, which adds kinetic energy; drift = split, the default, moves
//     positions instead, see lcp_method.h).
// Friction rows, rhs = 0, |lambda_t| <= mu lambda_n (normal_row, mu).
// Material rules are those of contact_row.h (e = max, mu = geometric mean).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/constraint_row.h"
#include "service/physics/world.h"

namespace contactsim {

struct ContactRowOptions {
  double h = 1.0 / 240.0;               // s
  double restitution_threshold = 0.01;  // m/s
  double slop = 1e-3;                   // m
  double baumgarte_erp = 0.0;           // 1/step; 0 without Baumgarte
};

// A row along unit d at contact point p between bodies a and b (-1: world).
ConstraintRow DirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d);

// Appends three rows per contact in contact order: normal, t1, t2. `before`
// holds the body velocities at the step's start (restitution); the row
// Jacobians use the world's current poses.
void AppendContactRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                       const ContactRowOptions& options, std::vector<ConstraintRow>* rows);

}  // namespace contactsim
