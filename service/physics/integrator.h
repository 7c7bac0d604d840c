// Semi-implicit (symplectic) Euler for rigid bodies: momenta first from the
// accumulated forces, then positions from the new velocities.
#pragma once

#include "service/physics/world.h"

namespace contactsim {

// P += F dt, L += tau dt for dynamic bodies (F, tau as accumulated).
void IntegrateMomenta(World& world, double dt);

// x += v dt; q advanced with L held fixed by the implicit midpoint rule
// (energy and |L| conserved for a torque-free body). Static bodies stay;
// kinematic bodies move with their set velocity.
void IntegratePositions(World& world, double dt);
// The same for one body (a solver's parallel loop over the bodies).
void IntegratePosition(RigidBody& body, double dt);

// The rotation q after time h with the world angular momentum L_W held
// fixed: the implicit midpoint rule on Euler's equations in the body frame,
// L_b' = L_b x w_b,
//   L1 = cay(-h w^) L0,  w = I_b^-1 (L0 + L1) / 2,
// and q1 = q cay(h w^) (quaternion (1, h w / 2) normalised). The midpoint
// rule conserves every quadratic invariant, here |L| and the kinetic energy
// L_b . I_b^-1 L_b / 2, so a torque-free body neither gains nor loses
// energy (an explicit update drifts by O(1) over 10^4 steps).
Quat MidpointRotation(const Quat& q, const Vec3& L_W, const Mat3& inv_inertia_body, double h);

// Moves one body for time h under its accumulated force and torque alone:
// P += F h, L += tau h, x += v0 h + F/(2m) h^2 (exact for a constant force),
// q as in IntegratePositions.
void AdvanceBallistic(RigidBody& body, double h);

}  // namespace contactsim
