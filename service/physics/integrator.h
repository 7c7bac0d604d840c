// Semi-implicit (symplectic) Euler for rigid bodies: momenta first from the
// accumulated forces, then positions from the new velocities.
#pragma once

#include "service/physics/world.h"

namespace contactsim {

// P += F dt, L += tau dt for dynamic bodies (F, tau as accumulated).
void IntegrateMomenta(World& world, double dt);

// x += v dt; q <- exp(w dt / 2) q, renormalised. Static bodies stay; kinematic
// bodies move with their set velocity.
void IntegratePositions(World& world, double dt);

// Moves one body for time h under its accumulated force and torque alone:
// P += F h, L += tau h, x += v0 h + F/(2m) h^2 (exact for a constant force),
// q <- exp(w h / 2) q with the new w.
void AdvanceBallistic(RigidBody& body, double h);

}  // namespace contactsim
