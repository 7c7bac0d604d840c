#include "service/contact/penalty/penalty_force.h"

#include <algorithm>
#include <cmath>

#include "service/physics/portable_math.h"

namespace contactsim {

NormalLaw EvaluateNormalLaw(const PenaltyParams& p, double depth, double vn, double nc, double damping, double kp) {
  NormalLaw law;
  if (p.model == "linear") {
    law.k = kp / nc;
    if (depth > 0.0) {
      law.c = damping / nc;
      law.lambda0 = (kp * depth - damping * vn) / nc;
    } else {
      law.lambda0 = kp * depth / nc;
    }
    return law;
  }
  if (depth <= 0.0) return law;
  const double factor = 1.0 - 1.5 * damping * vn;
  // separating so fast that the damping would pull: no force, no slope
  if (factor <= 0.0) return law;
  const double dn = portable::Pow(depth, p.hc_exponent);
  law.lambda0 = kp * dn * factor / nc;
  law.k = p.hc_exponent * kp * portable::Pow(depth, p.hc_exponent - 1.0) * factor / nc;
  law.c = 1.5 * damping * kp * dn / nc;
  return law;
}

double NoTensionRestitution(double zeta) {
  // unit natural frequency; x(t) the penetration after impact at speed 1,
  // beta = zeta. The contact ends at the first t > 0 where the force
  // x + 2 zeta x' vanishes; e = -x'(t).
  const double b = zeta;
  if (std::abs(zeta - 1.0) < 1e-9) {
    // critical: x = t e^-t, force e^-t (2 - t) = 0 at t = 2
    return portable::Exp(-2.0);
  }
  if (zeta < 1.0) {
    // x = e^-bt sin(wd t) / wd: (1 - 2 b^2) sin + 2 b wd cos = 0
    const double wd = std::sqrt(1.0 - b * b);
    const double phase = portable::Atan2(2.0 * b * wd, -(1.0 - 2.0 * b * b));  // in (0, pi)
    const double t = phase / wd;
    return -portable::Exp(-b * t) * (wd * portable::Cos(phase) - b * portable::Sin(phase)) / wd;
  }
  // x = e^-bt sinh(wo t) / wo: tanh(wo t) = y = 2 b wo / (2 b^2 - 1) < 1, so
  // wo t = atanh y = ln((1 + y) / (1 - y)) / 2, and
  // -e^-bt (cosh wo t - b / wo sinh wo t) in exponentials alone
  const double wo = std::sqrt(b * b - 1.0);
  const double y = 2.0 * b * wo / (2.0 * b * b - 1.0);
  const double t = 0.5 * portable::Log((1.0 + y) / (1.0 - y)) / wo;
  return -0.5 * (portable::Exp((wo - b) * t) * (1.0 - b / wo) + portable::Exp(-(wo + b) * t) * (1.0 + b / wo));
}

double ZetaFromRestitution(double e) {
  if (e >= 1.0) return 0.0;
  double lo = 0.0, hi = kMaxZeta;
  if (NoTensionRestitution(hi) >= e) return hi;
  // NoTensionRestitution falls monotonically from 1 at zeta = 0
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (NoTensionRestitution(mid) > e) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double DampingFromRestitution(double e, double kp, double m_eff) {
  return 2.0 * ZetaFromRestitution(e) * std::sqrt(kp * m_eff);
}

double HuntCrossleyAlpha(double e, double impact_speed) {
  const double ee = std::max(e, kMinHuntCrossleyRestitution);
  return 16.0 * (1.0 - ee) / (15.0 * ee * std::max(impact_speed, kMinImpactSpeed));
}

}  // namespace contactsim
