// The explicit step of the penalty method: one detection per world step,
// then sub-steps of symplectic Euler over the rows built at the step's
// start, each point's depth carried forward with the bodies' motion.
//
// Why sub-steps without re-detection: a contact of contact_time T
// (penalty_stiffness.h) must be resolved in time for its rebound to come
// out right, omega h <= max_omega_h (0.15) with omega = sqrt(kp / m_eff),
// pi / T for a body on the ground: 22 sub-steps of a 1/240 s step at
// T = 4 ms; detecting every sub-step would cost the narrowphase each time. Within one step the contact frame
// is held (normal n, lever arms turned with their bodies) and the depth is
// d = d0 - n . (dp_B - dp_A), dp the displacement of the body's material
// point since the step's start, dp = dx + (R R0^T - 1) r0 (the separation
// update of Box2D v3's soft step, Catto, "Solver2D", 2024). The detection
// margin is speculative (SpeculativeMargin), so a contact that begins
// within the step is already a row.
//
// Each sub-step of h, per engaged row (stage 1 for every row, then with
// impacts = sequential the impact stage of penalty_impacts.h on the rows
// that stage 1 found struck, then stages 2-4):
//  1. depth and relative velocity at the current poses and velocities; the
//     friction anchor advances by the last sub-step's slip, s += h v_t;
//  2. the normal law (penalty_force.h) with each dashpot c integrated
//     implicitly against its point's inverse effective mass K, times the
//     number of pairs n_b touching the busier of its dynamic bodies:
//     c' = c / (1 + h n_b c K). For a lone pair (one sphere, or a box on
//     four corners, each c / 4 against a corner's K) it is the force a
//     dashpot integrated implicitly gives, the same at every mass, so the
//     restitution is too; n_b bounds the damping a body feels from all its
//     pairs by 1 / h, as Gershgorin's theorem would with equal pairs. Why:
//     a sphere of the pile has a dozen overdamped neighbours, whose
//     explicit dashpots together reversed its velocity each sub-step; and
//     the Gershgorin bound over the points themselves counted a landing
//     box's four corners against each other (their rotations cancel for
//     the bounce), cut its damping by a quarter and it rebounded to 0.31 h.
//     A pair's points together are bounded by the largest eigenvalue of
//     their cut dashpots' share (penalty_damping_bound.h): a light hull's
//     three overdamped points rang on its rocking mode;
//  3. onset: a point that starts to penetrate at depth d missed the dashpot
//     impulse c d of its way in; it is added over the sub-step, capped so
//     that with the dashpot it takes at most the approach momentum
//     m_share |vn| (without the cap an overdamped dashpot sent a ball back
//     up as fast as it came);
//  4. friction: f_t = -kt s - ct' v_t onto the Coulomb disk; a slide moves
//     the anchor so that the spring alone carries the force
//     (penalty_friction.h);
// then P += F h, the joints' velocity solve, x += v h, the joints' drift.
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_impacts.h"
#include "service/contact/penalty/penalty_params.h"
#include "service/contact/penalty/penalty_row.h"
#include "service/physics/world.h"

namespace contactsim {

struct ExplicitStats {
  int substeps = 0;
  double max_penetration = 0.0;  // m, deepest point at any sub-step
};

// The sub-steps for a world step of dt: params.substeps at least, as many
// as a single contact needs to resolve its rebound (omega_point dt /
// max_omega_h) and as stability needs (omega_bound dt / 1,
// penalty_stiffness.h), at most 1000.
int ExplicitSubsteps(const World& world, const std::vector<PenaltyRow>& rows, const PenaltyParams& params,
                     double dt);

// Advances the world by dt in `substeps` sub-steps over `rows` (built at the
// step's start). Each body's force and torque must hold the external
// wrench; they are restored to it. Leaves in each row its last sub-step's
// lambda, ft, sliding, depth and anchor (stretch advanced by the slip).
// With params.impacts = sequential, each sub-step first resolves the impacts
// of its struck components by `impacts` (penalty_impacts.h).
ExplicitStats ExplicitStep(World& world, std::vector<PenaltyRow>& rows, const PenaltyParams& params, double dt,
                           int substeps, PenaltyImpacts* impacts);

}  // namespace contactsim
