// Joints in the xpbd method as positional constraints with compliance
// (Mueller, Macklin, Chentanez, Jeschke and Kim 2020, "Detailed rigid body
// simulation with extended position based dynamics", SCA, section 3.3.3
// "Joints", and Algorithm 3 for the angle limits), solved in the same
// Gauss-Seidel sweep as the contacts, once per position iteration of a
// sub-step. Each correction is one XPBD update (positional_correction.h):
// dlambda = (c - alpha~ lambda) / (w_A + w_B + alpha~) along one direction,
// the multipliers accumulating over the sub-step's iterations.
//
// Per joint, angular corrections first, then the positional one (as the
// paper orders them, so that the attachment point is met last and exactly
// for a rigid joint between two bodies):
//   hinge axes: B turns about n = a_B x a_A by asin|a_B x a_A| so that its
//     axis lines up with A's (eq. "dq_hinge = a_1 x a_2");
//   hinge limits: when the hinge angle (HingeAngle, physics/joint.h) is
//     outside [lower, upper], B turns about A's axis by the excess back
//     (Algorithm 3, limitAngle; plastic, no bounce);
//   weld: B turns by the rotation e = q_A rest q_B^-1 that restores the
//     creation pose, angle 2 atan2(|vec e|, w), axis vec e / |vec e|;
//   attachment (ball, hinge, fixed): the anchor of B moves onto the anchor
//     of A, c = |p_A - p_B| along (p_A - p_B) / c;
//   distance: c = |p_A - p_B| - length along the same direction.
// The world end is a static body at the origin (its anchor in world
// coordinates), which no correction moves.
//
// Drift: with zero compliance a lone joint is met exactly after each of its
// corrections; coupled joints are met to the Gauss-Seidel residual, which
// shrinks as h^2 with the sub-steps (the paper's argument) but grows with a
// chain's length, so rigid joints are then projected together by a Newton
// step after the sweeps (xpbd_method.h, 2b). The joints' geometry has no
// velocity rows: the sub-step's velocities come from the positions
// (xpbd_method.h). Damping, friction and the actuators' drives act on those
// velocities, as velocity rows before the positions move (xpbd_method.h, 2a).
#pragma once

#include <array>
#include <vector>

#include "service/physics/world.h"

namespace contactsim {

// Accumulated multipliers of one joint in a sub-step: angular, limit,
// positional (kg m^2 or kg m, the positional impulses).
using XpbdJointLambda = std::array<double, 3>;

// One XPBD pass over every joint of the world, in joint order; alpha_tilde =
// compliance / h^2 (1/kg for the positional, 1/(kg m^2) for the angular
// corrections). `lambdas` holds one entry per joint (resized and zeroed by
// the caller at the start of each sub-step).
void SolveXpbdJoints(World& world, double alpha_tilde, std::vector<XpbdJointLambda>* lambdas);

}  // namespace contactsim
