// A rigid constraint made soft by a spring-damper with a frequency and a
// damping ratio, expressed for one implicit (backward Euler) step of h so
// that the stiffness never depends on the masses (Catto, "Soft Step",
// Solver2D, 2024; the constraint-force-mixing derivation of Erin Catto's
// GDC 2011 "Soft Constraints"). With omega = 2 pi f, zeta the damping ratio,
//   a1 = 2 zeta + h omega,  a2 = h omega a1,  a3 = 1 / (1 + a2),
// a velocity row's impulse is
//   lambda += -m_eff mass_scale (J v + bias_rate C) - impulse_scale lambda,
// with bias_rate = omega / a1, mass_scale = a2 a3, impulse_scale = a3: a
// spring of stiffness m_eff omega^2 and damping 2 m_eff zeta omega, whatever
// m_eff is, so a heavy box on a light one settles like a light box on a
// light one.
#pragma once

#include <cmath>

namespace contactsim {

struct Softness {
  double bias_rate = 0.0;      // 1/s
  double mass_scale = 1.0;
  double impulse_scale = 0.0;
};

inline Softness MakeSoftness(double hertz, double damping_ratio, double h) {
  if (hertz <= 0.0) return Softness{};
  const double omega = 2.0 * M_PI * hertz;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return Softness{omega / a1, a2 * a3, a3};
}

// The same spring with its stiffness taken from a mass `ratio` = m_eff /
// m_load times the effective mass, so that a row under m_load's weight
// compresses as a row of m_load would: the row's compliance,
// impulse_scale / (mass_scale m_eff) = 1 / (a2 m_eff), becomes
// ratio / (a2 m_eff); the bias rate, how fast it pushes out, is unchanged.
// With a2 = mass_scale / impulse_scale:
//   mass_scale' = a2 / (a2 + ratio),  impulse_scale' = ratio / (a2 + ratio).
inline Softness LoadedSoftness(const Softness& s, double ratio) {
  if (s.impulse_scale <= 0.0) return s;
  const double a2 = s.mass_scale / s.impulse_scale;
  return Softness{s.bias_rate, a2 / (a2 + ratio), ratio / (a2 + ratio)};
}

}  // namespace contactsim
