// One command to a simulated Schunk WSG gripper (Drake's
// lcmt_schunk_wsg_command), after the checks that need no world; the
// separation's range depends on the model and is checked when the command is
// applied (WsgDriver::Apply).
#pragma once

#include <cstdint>

#include "service/physics/status.h"

namespace contactsim {

struct WsgCommand {
  int64_t utime = 0;                // us, the sender's clock (not used for timing)
  double target_position_mm = 0.0;  // mm, the wanted separation of the fingers
  double force = 0.0;               // N, the largest grip force, > 0
};

// lcmt_schunk_wsg_command is 24 bytes and a fingerprint; nothing longer is one.
constexpr int kMaxWsgCommandBytes = 64;

// Decodes and checks an encoded lcmt_schunk_wsg_command: the size limit, the
// encoding's bounds, the fingerprint, a finite target and a finite force
// > 0 (a force of 0 would leave the fingers no effort to move with). On
// error the status names the field and value, and *out is untouched but for
// utime, set once the message could be read.
Status DecodeWsgCommand(const void* data, int size, WsgCommand* out);

}  // namespace contactsim
