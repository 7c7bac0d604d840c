// One contact point's impulse along a row applied to its two bodies, shared
// by the solvers that keep their own body velocities (soft and xpbd bodies,
// the sequential impacts' copy).
#pragma once

#include "service/physics/math.h"

namespace contactsim {

// Adds j d to B's momentum and -j d to A's, through the angular responses
// ia = I_A^-1 (r_A x d) and ib = I_B^-1 (r_B x d) computed once a point.
// A body without inverse mass (static or kinematic) is never written, so
// threads that share one may run at once (block_colours.h).
template <class Body>
inline void PushImpulse(double j, const Vec3& d, const Vec3& ia, const Vec3& ib, Body& A, Body& B) {
  if (A.inv_mass > 0.0) {
    A.v -= (A.inv_mass * j) * d;
    A.w -= j * ia;
  }
  if (B.inv_mass > 0.0) {
    B.v += (B.inv_mass * j) * d;
    B.w += j * ib;
  }
}

}  // namespace contactsim
