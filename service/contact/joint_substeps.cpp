#include "service/contact/joint_substeps.h"

#include <algorithm>

namespace contactsim {

StepStats StepInSubsteps(World& world, int count, ContactValueKind kind,
                         const std::function<StepStats(ContactSet*)>& substep, ContactSet* contacts) {
  const double dt = world.dt;
  world.dt = dt / count;
  StepStats total;
  for (int i = 0; i < count; ++i) {
    const StepStats s = substep(contacts);
    total.iterations += s.iterations;
    total.substeps += s.substeps;
    total.residual = std::max(total.residual, s.residual);
    total.max_penetration = std::max(total.max_penetration, s.max_penetration);
    total.stiffness = std::max(total.stiffness, s.stiffness);
    total.contacts = s.contacts;
  }
  world.dt = dt;
  if (kind == ContactValueKind::kImpulse) {
    for (Contact& c : *contacts) {
      c.normal_value *= count;
      c.tangent_value *= count;
    }
  }
  world.FinishStep();
  return total;
}

}  // namespace contactsim
