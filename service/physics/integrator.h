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

}  // namespace contactsim
