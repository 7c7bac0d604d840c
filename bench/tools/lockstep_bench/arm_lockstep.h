// Lockstep with joint commands: one controller driving a fixed-base robot
// arm (pybullet_data's KUKA iiwa) through per-step joint targets, each
// cycle one STATE and JOINT_STATE out and one input with seven joint
// commands back (docs/actuators.md, "Joint channels").
#pragma once

#include <string>

#include "contactsim/client.h"

namespace contactsim::bench {

struct ArmLockstepResult {
  double cycles_per_second = 0.0;
  int state_bytes = 0;  // STATE and JOINT_STATE of one step
  int input_bytes = 0;  // an input of seven joint targets
  int joints = 0;
  std::string error;
};

// Loads `urdf` with its base fixed and standing gains on its joints, then
// for `seconds` answers every STATE with targets along a slow sine.
ArmLockstepResult MeasureArmLockstep(Client& client, const std::string& urdf, double seconds);

}  // namespace contactsim::bench
