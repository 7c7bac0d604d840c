// How stiff the penalty method's springs are, and how short its explicit
// sub-steps must be for them.
//
// Stiffness from a contact time (contact_time = T > 0, linear law): a pair's
// normal spring is k = m_s (pi / T)^2, so that a body of mass m_s on a fixed
// plane rebounds after half a period, T, whatever its mass, and the damping
// kd = 2 zeta(e) sqrt(k m_eff) (penalty_force.h) gives restitution e at
// every mass (MuJoCo's solref time constant sets its soft constraints the
// same way, from the effective mass: Todorov, "Convex and analytically-
// invertible dynamics with contacts and constraints", ICRA 2014). m_s is the
// heaviest dynamic body of the pair's contact island (bodies joined through
// dynamic-dynamic contacts), not the pair's own mass: a 0.02 kg box under a
// 20 kg box would otherwise sink m g T^2 / (0.02 kg pi^2) = 0.3 m into the
// ground at T = 4 ms. An island of equal bodies rests m g / k = g T^2 / pi^2
// deep per layer and body it carries (16 um at T = 4 ms). The tangential
// spring is as stiff as the normal one.
//
// The explicit step's sub-step (penalty_explicit.h): symplectic Euler on
// u' = M^-1 (f - K x) is stable while omega_max h < 2, omega_max^2 the
// largest eigenvalue of M^-1 K = M^-1 J^T diag(k) J over every normal and
// tangential spring. Power iteration in the metric of M (where the matrix
// is symmetric) gives it from below in a few products of O(rows) each
// (Golub and Van Loan, "Matrix Computations", 8.2.1); a Gershgorin bound
// over the points, |J_i M^-1 J_j^T| <= sqrt(K_ib K_jb), was twice as
// large on the standard scenes and doubled the sub-steps.
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/penalty/penalty_params.h"
#include "service/contact/penalty/penalty_row.h"
#include "service/physics/world.h"

namespace contactsim {

// For each body index, the mass (kg) of the heaviest dynamic body of its
// contact island (0 for static and kinematic bodies).
std::vector<double> IslandHeaviestMass(const World& world, const ContactSet& contacts);

// The pair stiffness (N/m) of a contact time: m_s (pi / T)^2.
double StiffnessFromContactTime(double heaviest_mass, double contact_time);

// The highest contact frequencies (rad/s) of the engaged rows: `point` the
// largest sqrt(kp / m_eff) of a pair's normal spring against its effective
// mass, the frequency its damping and restitution are set for (what a
// bounce must resolve; pairs of restitution 0 count with
// sqrt(kp / m) / kSettleSlack, having no bounce to resolve); `estimate` omega_max of every normal
// and tangential spring together (what the step's stability needs; several
// times `point` for a body held by many), the Rayleigh quotient after
// kPowerIterations products from a fixed start vector, so deterministic.
// It approaches omega_max from below; the stability margin
// (penalty_explicit.h) covers the remainder. Every engaged row counts,
// touching or not: leaving out the gaps that the approach speed alone
// would not close within dt made box_rain diverge (570 J after 2.5 s), its
// boxes pushed into them by others.
constexpr int kPowerIterations = 20;
// A pair of restitution 0 has no bounce to resolve, only its settling:
// sqrt(kp / m) h <= kSettleSlack max_omega_h, m the lighter of m_s, the
// mass its stiffness was set for (pi / contact_time; m_eff for a fixed kp),
// and 2 m_eff. For equal masses and a body on the ground m = m_s, not the
// faster relative mode (sqrt(2) pi / T for two equal bodies), which costs
// the pyramid and the pile a quarter more sub-steps for no measured gain;
// a light body pressed by a heavy one settles at its own frequency,
// sqrt(kp / m_eff), 30 times pi / T under a 1,000 times heavier plank,
// and with m_s alone it flew off (docs/methods/penalty.md, "Explicit
// integrator"). A
// 0.2 m box held by mu = 0.7 on a 30 degree slope moved 1e-19 m in 2 s at
// 1.5 and crept 1 um at 2 (its uphill corners slip and hand their load on).
constexpr double kSettleSlack = 1.5;
struct ContactOmega {
  double point = 0.0;
  double estimate = 0.0;
  // the largest m_s of an engaged pair over the lighter of its dynamic
  // bodies: how much heavier than a body the springs holding it were set for
  double mass_ratio = 1.0;
};
ContactOmega ContactOmegas(const World& world, const std::vector<PenaltyRow>& rows);

// Gap (m) within which contacts are detected for an explicit step of dt:
// margin plus the largest distance two bodies can close in dt, twice the
// largest speed of a body's points (|v| + |w| r, r its bounding radius) plus
// gravity's |g| dt, so that no contact begins inside the step unseen.
double SpeculativeMargin(const World& world, double margin, double dt);

// Half the diagonal of the body's bounding box (m): no point of it is farther
// from its centre of mass.
double BoundingRadius(const RigidBody& body);

// |v| + |w| r of a body (m/s), r its bounding radius; 0 for static bodies.
double FastestPointSpeed(const RigidBody& body);

}  // namespace contactsim
