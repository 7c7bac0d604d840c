// One sequential-impulse update of a contact point's Coulomb disk
// (Catto 2005: accumulated impulses, clamped), shared by the methods that
// sweep their points one by one (impulse, soft).
//
// The per-axis update lambda_k <- lambda_k - m_tk u_k (m_tk = 1 / K_kk, u
// the slip along t1, t2) solves a sticking point; for a sliding one its
// radial projection onto the disk settles where lambda_t is parallel to
// -(m_t1 u_1, m_t2 u_2), not to -u: wherever the point's two effective
// masses differ (a corner of a plank, lever arms of unequal reach along t1
// and t2), the friction leaves the slip's direction and dissipates less
// than Coulomb's maximal dissipation (Moreau 1988) allows. A plank of
// 60 x 20 cm spun on its face lost its spin 9.5% slower than its corners'
// friction mu m g / 4 at r = sqrt(a^2 + b^2) brakes it.
// So when the per-axis update leaves the disk, the point slides and the
// update is taken along the slip instead, with the slip's own effective
// mass 1 / (u^T K u / |u|^2), K the pair's 2 x 2 inverse mass:
//   lambda_t <- P_disk(lambda_t - u |u|^2 / (u^T K u)),
// whose fixed point on the disk's rim is lambda_t = -mu lambda_n u / |u|.
// (lcp's PGS takes one step size for both rows, 2 / tr K, for the same
// reason: pgs.h.)
#pragma once

#include <cmath>

namespace contactsim {

// Updates the accumulated tangent impulses (l1, l2) of a point with slip
// (u1, u2) (m/s), effective masses m1 = 1 / K_11, m2 = 1 / K_22 and
// coupling k12 = K_12 (1/kg), within |l| <= limit.
inline void SlipFrictionStep(double limit, double u1, double u2, double m1, double m2, double k12, double* l1,
                             double* l2) {
  double n1 = *l1 - m1 * u1;
  double n2 = *l2 - m2 * u2;
  double squared = n1 * n1 + n2 * n2;
  if (squared > limit * limit) {
    const double uu = u1 * u1 + u2 * u2;
    const double uku = (m1 > 0.0 ? u1 * u1 / m1 : 0.0) + 2.0 * k12 * u1 * u2 + (m2 > 0.0 ? u2 * u2 / m2 : 0.0);
    if (uu > 0.0 && uku > 0.0) {
      const double step = uu / uku;
      n1 = *l1 - step * u1;
      n2 = *l2 - step * u2;
      squared = n1 * n1 + n2 * n2;
    }
    if (squared > limit * limit) {
      // not std::hypot: its overflow guard cost 15% of impulse's step on the pyramid
      const double scale = squared > 0.0 ? limit / std::sqrt(squared) : 0.0;
      n1 *= scale;
      n2 *= scale;
    }
  }
  *l1 = n1;
  *l2 = n2;
}

}  // namespace contactsim
