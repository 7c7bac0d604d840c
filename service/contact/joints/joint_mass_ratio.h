// Whether a world's joints join bodies of very different masses, which the
// velocity-level methods treat apart: a joint solve over a whole step
// spins light links up under a heavy body until it diverges (a 20 kg box
// on four 0.02 kg links, docs/physics.md "Mass ratios"), so impulse, lcp and
// penalty take such steps in sub-steps (joint_substeps.h). (One
// Gauss-Seidel sweep, which converges at about 1 - m_light / m_heavy, left
// such a chain open under xpbd too; xpbd now projects every rigid joint
// after its sweeps, xpbd_method.h.)
#pragma once

#include "service/physics/world.h"

namespace contactsim {

// True when some set of dynamic bodies joined by joints holds a body at
// least `ratio` times heavier than another (ratio <= 0: never).
bool JointMassRatioAtLeast(const World& world, double ratio);

}  // namespace contactsim
