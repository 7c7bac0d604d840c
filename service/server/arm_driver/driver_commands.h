// The one decoding of Drake's driver commands into the server's Command, for
// the live path (CommandIntake) and the journal's replay (timeline.cpp)
// alike: the record kind says whose command it is, the arm's (in the
// configured protocol) or the WSG gripper's.
#pragma once

#include <cstdint>

#include "service/physics/status.h"
#include "service/server/arm_driver/arm_protocol.h"
#include "service/server/command.h"

namespace contactsim {

// Fills cmd->kind and the arm's or the gripper's fields from an encoded
// message; *utime is the message's once it could be read, else -1.
// `arm_protocol` is the arm driver's (null without one: its commands are
// refused). RecordKind other than kArmCommand and kWsgCommand: InvalidArgument.
Status DecodeDriverCommand(RecordKind record, const ArmProtocol* arm_protocol, const void* data, int size,
                           Command* cmd, int64_t* utime);

}  // namespace contactsim
