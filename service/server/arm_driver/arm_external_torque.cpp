#include "service/server/arm_driver/arm_external_torque.h"

#include <map>

#include "service/contact/contact_wrench.h"

namespace contactsim {

std::vector<double> ArmExternalTorques(const World& world, const ArmJoints& arm, const ContactSet& contacts,
                                       ContactValueKind kind, const std::vector<TimedWrench>& wrenches) {
  // force and torque (about the centre of mass) on each of the arm's bodies
  const std::vector<ContactWrench> touch = SumContactWrenches(world, arm.bodies, contacts, kind);
  std::map<BodyId, BodyLoad> on;
  for (size_t k = 0; k < arm.bodies.size(); ++k) {
    on[arm.bodies[k]] = {touch[k].normal_force + touch[k].friction_force, touch[k].torque};
  }
  for (const TimedWrench& w : wrenches) {
    auto it = on.find(w.body);
    if (it == on.end()) continue;  // not the arm's
    it->second.force += w.force;
    it->second.torque += w.torque;
  }
  return JointAxisTorques(world, arm, [&](BodyId id) {
    const auto it = on.find(id);
    return it == on.end() ? BodyLoad{} : it->second;
  });
}

}  // namespace contactsim
