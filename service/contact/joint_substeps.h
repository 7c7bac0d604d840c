// A step taken as equal sub-steps, for velocity-level methods whose joint
// solve over a whole step loses a heavy body hung from light links: the
// links' spin over a step, w h, grows until the solve diverges, and a
// quarter step holds the same chain to round-off (docs/physics.md, "Mass
// ratios"). The world's clock advances once, by the whole step.
#pragma once

#include <functional>

#include "service/contact/contact_method.h"
#include "service/contact/joints/joint_mass_ratio.h"
#include "service/contact/param_table.h"

namespace contactsim {

// The two parameters of the methods that sub-step such worlds, declared once.
template <class P>
ParamField<P> JointSubstepRatioParam(double P::*member) {
  return DoubleParam("joint_substep_ratio", member, 0.0, 1e12, "",
                     "a world whose joints join a body this many times heavier than another steps in "
                     "joint_substeps sub-steps (joint_substeps.h); 0 = never");
}
template <class P>
ParamField<P> JointSubstepsParam(int P::*member) {
  return IntParam("joint_substeps", member, 1, 64, "", "sub-steps of such a step");
}

// The sub-steps a step of `world` takes: `count` when its joints join a body
// `ratio` times heavier than another, else 1.
inline int JointSubstepCount(const World& world, double ratio, int count) {
  return JointMassRatioAtLeast(world, ratio) ? count : 1;
}

// Runs `substep` (one step of the method over world.dt, without
// World::FinishStep) `count` times over world.dt / count, then finishes the
// step once. The contacts reported are the last sub-step's, their values
// (impulses over a sub-step) scaled by `count` when `kind` is kImpulse, so
// that they stand for the step; forces stand as they are. Stats add up,
// except max_penetration (the largest) and contacts (the last sub-step's).
StepStats StepInSubsteps(World& world, int count, ContactValueKind kind,
                         const std::function<StepStats(ContactSet*)>& substep, ContactSet* contacts);

}  // namespace contactsim
