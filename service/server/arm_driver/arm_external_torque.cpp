#include "service/server/arm_driver/arm_external_torque.h"

#include <map>

#include "service/contact/contact_wrench.h"

namespace contactsim {

std::vector<double> ArmExternalTorques(const World& world, const ArmJoints& arm, const ContactSet& contacts,
                                       ContactValueKind kind, const std::vector<TimedWrench>& wrenches) {
  // force and torque (about the centre of mass) on each of the arm's bodies
  const std::vector<ContactWrench> touch = SumContactWrenches(world, arm.bodies, contacts, kind);
  std::map<BodyId, std::pair<Vec3, Vec3>> on;
  for (size_t k = 0; k < arm.bodies.size(); ++k) {
    on[arm.bodies[k]] = {touch[k].normal_force + touch[k].friction_force, touch[k].torque};
  }
  for (const TimedWrench& w : wrenches) {
    auto it = on.find(w.body);
    if (it == on.end()) continue;  // not the arm's
    it->second.first += w.force;
    it->second.second += w.torque;
  }
  std::vector<double> tau;
  for (size_t i = 0; i < arm.joints.size(); ++i) {
    const Joint& j = *world.FindJoint(arm.joints[i]);
    const RigidBody* child = world.Find(j.body_b);
    const Vec3 p_W = AnchorWorld(j.anchor_b, child);
    const Vec3 a_W = BodyOrientation(child) * j.axis_b;
    Vec3 moment = Vec3::Zero();
    for (BodyId id : arm.outboard[i]) {
      const auto it = on.find(id);
      if (it == on.end()) continue;
      moment += (world.Find(id)->x - p_W).cross(it->second.first) + it->second.second;
    }
    tau.push_back(a_W.dot(moment));
  }
  return tau;
}

}  // namespace contactsim
