// One command to a simulated arm from Drake's arm-driver protocol
// (lcmt_iiwa_command), after the checks that need no world: the decoder is
// total, as the server's own channels' are (command_channels.h), so bytes
// from the network never reach the generated decoder unchecked and nothing
// thrown leaves it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

struct ArmCommand {
  int64_t utime = 0;              // us, the sender's clock (not used for timing)
  std::vector<double> position;   // rad, one target per joint; empty: torque only
  std::vector<double> torque;     // N m, feed-forward per joint; empty: none
};

// The largest lcmt_iiwa_command taken: 64 joints' positions and torques
// with the header are about 1 kB; an arm has 7.
constexpr int kMaxArmCommandBytes = 4096;

// Decodes and checks an encoded lcmt_iiwa_command: the size limit, the
// encoding's bounds (wire_check.hpp), the fingerprint, and finite values.
// The counts are checked against the arm when it is applied
// (ArmDriver::Apply). On error the status says why, and *out is untouched
// but for utime, set once the message could be read (to name it in a reply).
Status DecodeIiwaCommand(const void* data, int size, ArmCommand* out);

}  // namespace contactsim
