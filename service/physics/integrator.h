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

// Moves one body for time h under its accumulated force and torque alone:
// P += F h, L += tau h, x += v0 h + F/(2m) h^2 (exact for a constant force),
// q as in IntegratePositions.
void AdvanceBallistic(RigidBody& body, double h);

}  // namespace contactsim
