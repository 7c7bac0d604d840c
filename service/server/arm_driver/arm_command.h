// One command to a simulated arm from one of Drake's arm-driver protocols
// (lcmt_iiwa_command, lcmt_panda_command), after the checks that need no
// world: the decoders are total, as the server's own channels' are
// (command_channels.h), so bytes from the network never reach a generated
// decoder unchecked and nothing thrown leaves them. Both protocols land in
// the same ArmCommand: which arrays it holds says which inputs the drives
// take (ArmDriver::Apply).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

struct ArmCommand {
  int64_t utime = 0;              // us, the sender's clock (not used for timing)
  std::vector<double> position;   // rad, one target per joint; empty: no position target
  std::vector<double> velocity;   // rad/s, one target per joint; empty: none (0 with a position target)
  std::vector<double> torque;     // N m, feed-forward per joint; empty: none
};

// The largest command taken: 64 joints' positions, velocities and torques
// with the header are about 1.5 kB; an arm has 7.
constexpr int kMaxArmCommandBytes = 4096;

// Decodes and checks an encoded lcmt_iiwa_command: the size limit, the
// encoding's bounds (wire_check.hpp), the fingerprint, and finite values.
// The counts are checked against the arm when it is applied
// (ArmDriver::Apply). On error the status says why, and *out is untouched
// but for utime, set once the message could be read (to name it in a reply).
Status DecodeIiwaCommand(const void* data, int size, ArmCommand* out);

// The bits of lcmt_panda_command's control_mode_expected (Drake's
// PandaControlMode, the CONTROL_MODE_* constants of lcmt_panda_status).
constexpr int kPandaPositionMode = 1;
constexpr int kPandaVelocityMode = 2;
constexpr int kPandaTorqueMode = 4;

// Decodes and checks an encoded lcmt_panda_command as DecodeIiwaCommand
// does, and its mode: control_mode_expected must be a non-empty set of the
// three bits, and each array must be sent exactly when its bit is set (as
// Drake's PandaCommandReceiver requires). Every mode maps onto the joint
// drives (physics/joint_actuator.h), so every such set is served; another
// bit, no bit, or an array that disagrees with the bits is refused
// (InvalidArgument, naming the mode and the array), never ignored.
Status DecodePandaCommand(const void* data, int size, ArmCommand* out);

}  // namespace contactsim
