// Continuous collision detection of one primitive pair of the barrier
// method: how far along a Newton step the pair can move before its distance
// falls to a fraction of its current value. Additive CCD (Li, Kaufman and
// Jiang 2021, "Codimensional Incremental Potential Contact", sec. 4 and
// Alg. 1): every vertex of the two primitives moves linearly in alpha
// (affine maps are linear in q); with the common motion of the vertices
// taken out, no point of one primitive moves towards the other faster than
//   l = max_i |dv_i - c| + max_j |du_j - c|   (c: the vertices' mean motion)
// per unit alpha, so from a distance d(t) the pair cannot fall below the
// target before t + (d(t) - target) / l. Advancing t by that bound and
// measuring the distance again there converges on the time the target is
// reached, instead of stopping at the first (global, vertex-bound) estimate:
// pairs that slide past each other (a box resting on another) no longer cut
// every step to d / l. Every returned alpha is safe, however few iterations
// are taken.
#pragma once

#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/contact_primitives.h"

namespace contactsim {

struct CcdPair {
  const BodyGeometry* a = nullptr;
  const BodyGeometry* b = nullptr;
  Vec12 qa, qb;       // affine coordinates at alpha = 0
  Vec12 dqa, dqb;     // the step (zero for a body that does not move)
  PrimitivePair pair;
  double shift = 0.0; // m, subtracted from the distance (barrier_solver.h)
  double width = 0.0; // m, the pair's barrier width (a surface pair's choice of edge: surface_primitives.h)
  double signed_depth = 0.0;  // m, EvaluatePair's
  bool placed = false;  // a placed pair (barrier_solver.h): only its shifted distance counts
};

// l above: over the whole step no point of one primitive gets nearer to the
// other by more than this (m). (Against a static plane, whose side has no
// vertices, the point's whole motion.)
double RelativeMotionBound(const CcdPair& p);

// The same bound when the two sides move by different fractions of their
// steps (the islands of barrier_newton.cpp have their own line searches):
// no common motion is taken out, l = max_i |dv_i| + max_j |du_j|.
double SeparateMotionBound(const CcdPair& p);
// The largest alpha in [0, limit] found safe: the distance minus shift stays
// at or above fraction times its value at alpha = 0 (which must be > 0), and
// for a shifted pair (shift < 0) whose distance is positive, unless placed,
// the distance itself stays above fraction times its value.
// `limit` (at most 1) lets a caller that already has a smaller alpha from
// another pair skip the search.
double AdditiveCcd(const CcdPair& p, double fraction, double limit);

}  // namespace contactsim
