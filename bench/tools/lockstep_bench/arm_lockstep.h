// Lockstep with joint commands: one controller driving a fixed-base robot
// arm (pybullet_data's KUKA iiwa) through per-step joint targets, each
// cycle one STATE carrying the joints out (and JOINT_STATE beside it if the
// server's joint_state option is "always") and one input with seven joint
// commands back (docs/actuators.md, "Joint channels").
#pragma once

#include <sys/types.h>

#include <string>

#include "contactsim/client.h"

namespace contactsim::bench {

struct ArmLockstepResult {
  double cycles_per_second = 0.0;
  int state_bytes = 0;  // what the server sends a step: STATE, and JOINT_STATE when it comes too
  int input_bytes = 0;  // an input of seven joint targets
  int joints = 0;
  double cpu_per_cycle = 0.0;  // s on a CPU per cycle, the server's and this process's together
  double runs_per_cycle = 0.0;  // times their threads were put on a CPU per cycle (process_cpu.h)
  double joint_states_per_cycle = 0.0;  // JOINT_STATEs heard per cycle: 1 with joint_state "always", else 0
  std::string error;
};

// Loads `urdf` with its base fixed and standing gains on its joints, then
// for `seconds` answers every STATE with targets along a slow sine;
// `server` is the server's process id.
ArmLockstepResult MeasureArmLockstep(Client& client, const std::string& urdf, double seconds, pid_t server);

}  // namespace contactsim::bench
