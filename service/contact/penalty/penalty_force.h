// The normal force law of the penalty method at one contact point, and the
// damping that gives a wanted coefficient of restitution.
//
// Signs: depth d > 0 is penetration, vn = n . (v_B - v_A) at the point is the
// separating velocity (vn < 0 approaching), so the penetration rate is -vn.
// lambda >= 0 pushes B along +n and A along -n; it is never negative (no
// pull), which the callers enforce.
//
// linear (Parent, "Computer Animation", ch. 7.4, F = -d (kp - kd vn) / nc
// written with our signs):
//   lambda = (kp d - kd vn) / nc                          for d > 0
// hunt_crossley (Hunt and Crossley, "Coefficient of restitution interpreted
// as damping in vibroimpact", J. Appl. Mech. 42, 1975, eq. for lambda =
// (3/2) alpha k):
//   lambda = kp d^n (1 + (3/2) alpha (-vn)) / nc         for d > 0
// The damping of Hunt-Crossley vanishes with d, so the force starts at zero
// at impact (the linear dashpot jumps to kd |vn|).
// nc is the number of contact points of the body pair (penalty_row.h), so
// kp and kd are the stiffness and damping of the pair whatever its manifold.
#pragma once

#include "service/contact/penalty/penalty_params.h"

namespace contactsim {

// The force at the start of the step and its derivatives, for the explicit
// force and for the linearly implicit step.
struct NormalLaw {
  double lambda0 = 0.0;  // N, before the no-pull clamp
  double k = 0.0;        // N/m, d lambda / d depth (>= 0)
  double c = 0.0;        // N s/m, -d lambda / d vn (>= 0)
};

// `damping` is the pair's kd (linear, N s/m) or alpha (hunt_crossley, s/m).
// For d <= 0 (a predicted contact of the implicit step) the linear law is
// the spring alone, lambda0 = kp d / nc < 0, so that it engages only if the
// step closes the gap; there is no damping before the surfaces touch.
// Hunt-Crossley gives nothing for d <= 0 (its slope is zero there for n > 1).
// `kp` is the pair's stiffness (penalty_stiffness.h; p.kp in the overload).
NormalLaw EvaluateNormalLaw(const PenaltyParams& p, double depth, double vn, double nc, double damping, double kp);
inline NormalLaw EvaluateNormalLaw(const PenaltyParams& p, double depth, double vn, double nc, double damping) {
  return EvaluateNormalLaw(p, depth, vn, nc, damping, p.kp);
}

// Coefficient of restitution of the linear spring-dashpot that cannot pull
// (the contact ends when kp d - kd vn reaches zero, before d = 0), as a
// function of the damping ratio zeta = kd / (2 sqrt(kp m_eff)). Schwager and
// Poeschel, "Coefficient of restitution and linear-dashpot model revisited",
// Granular Matter 9, 2007. Without gravity; exact for the continuous model.
double NoTensionRestitution(double zeta);

// The inverse of NoTensionRestitution by bisection, zeta in [0, kMaxZeta].
// A dashpot that cannot pull always lets go with some speed (e -> 0 only as
// zeta -> infinity): NoTensionRestitution(1) = e^-2 ~ 0.135,
// NoTensionRestitution(10) = 0.0024, so restitutions below that give
// zeta = 10 (a rebound of 6e-6 of the drop height). The explicit step
// integrates each dashpot implicitly (penalty_explicit.h), so an overdamped
// dashpot stays stable.
constexpr double kMaxZeta = 10.0;
double ZetaFromRestitution(double e);

// kd (N s/m) for restitution e of a pair of stiffness kp and effective mass
// m_eff = 1 / (1/m_a + 1/m_b): kd = 2 zeta(e) sqrt(kp m_eff).
double DampingFromRestitution(double e, double kp, double m_eff);

// Hunt-Crossley alpha (s/m) for restitution e at impact speed v_in, from
// Flores, Machado, Silva and Martins, "On the continuous contact force
// models for soft materials in multibody dynamics", Multibody Syst. Dyn. 25,
// 2011: chi = 8 (1 - e) / (5 e) k / v_in for F = k d^n + chi d^n d', so with
// our (3/2) alpha k = chi, alpha = 16 (1 - e) / (15 e v_in). (Hunt and
// Crossley's own e = 1 - alpha v_in holds only near e = 1: it gives twice
// the rebound energy at e = 0.5.) Impact speeds below kMinImpactSpeed count
// as kMinImpactSpeed and restitutions below kMinHuntCrossleyRestitution as
// that, so that resting contacts and e -> 0 get bounded damping.
constexpr double kMinImpactSpeed = 0.1;  // m/s
constexpr double kMinHuntCrossleyRestitution = 0.1;
double HuntCrossleyAlpha(double e, double impact_speed);

}  // namespace contactsim
