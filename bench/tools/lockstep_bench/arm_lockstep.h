// Lockstep with joint commands: one controller driving a fixed-base robot
// arm (pybullet_data's KUKA iiwa) through per-step joint targets, each
// cycle one STATE and JOINT_STATE out and one input with seven joint
// commands back (docs/actuators.md, "Joint channels").
#pragma once

#include <sys/types.h>

#include <string>

#include "contactsim/client.h"

namespace contactsim::bench {

struct ArmLockstepResult {
  double cycles_per_second = 0.0;
  int state_bytes = 0;  // STATE and JOINT_STATE of one step
  int input_bytes = 0;  // an input of seven joint targets
  int joints = 0;
  double cpu_per_cycle = 0.0;  // s on a CPU per cycle, the server's and this process's together
  std::string error;
};

// Loads `urdf` with its base fixed and standing gains on its joints, then
// for `seconds` answers every STATE with targets along a slow sine;
// `server` is the server's process id.
ArmLockstepResult MeasureArmLockstep(Client& client, const std::string& urdf, double seconds, pid_t server);

}  // namespace contactsim::bench
