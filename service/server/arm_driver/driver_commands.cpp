#include "service/server/arm_driver/driver_commands.h"

namespace contactsim {

Status DecodeDriverCommand(RecordKind record, const ArmProtocol* arm_protocol, const void* data, int size,
                           Command* cmd, int64_t* utime) {
  *utime = -1;
  Status st;
  if (record == RecordKind::kArmCommand) {
    cmd->kind = Command::Kind::kArmCommand;
    cmd->arm.utime = -1;
    st = arm_protocol != nullptr ? arm_protocol->decode_command(data, size, &cmd->arm)
                                 : Status::FailedPrecondition("an arm command, but this server has no arm driver");
    *utime = cmd->arm.utime;
  } else if (record == RecordKind::kWsgCommand) {
    cmd->kind = Command::Kind::kWsgCommand;
    cmd->wsg.utime = -1;
    st = DecodeWsgCommand(data, size, &cmd->wsg);
    *utime = cmd->wsg.utime;
  } else {
    st = Status::InvalidArgument("record kind " + std::to_string(static_cast<int>(record)) +
                                 " is no driver's command");
  }
  return st;
}

}  // namespace contactsim
