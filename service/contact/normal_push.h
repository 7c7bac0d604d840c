// The normal impulse of one contact point applied to its two bodies, shared
// by the solvers that keep their own body velocities (soft and xpbd bodies,
// the sequential impacts' copy).
#pragma once

#include "service/physics/math.h"

namespace contactsim {

// Adds j n to B's momentum and -j n to A's, through the angular responses
// ia_n = I_A^-1 (r_A x n) and ib_n = I_B^-1 (r_B x n) computed once a point.
// A body without inverse mass (static or kinematic) is never written, so
// threads that share one may run at once (block_colours.h).
template <class Body>
inline void PushNormalImpulse(double j, const Vec3& n, const Vec3& ia_n, const Vec3& ib_n, Body& A, Body& B) {
  if (A.inv_mass > 0.0) {
    A.v -= (A.inv_mass * j) * n;
    A.w -= j * ia_n;
  }
  if (B.inv_mass > 0.0) {
    B.v += (B.inv_mass * j) * n;
    B.w += j * ib_n;
  }
}

}  // namespace contactsim
