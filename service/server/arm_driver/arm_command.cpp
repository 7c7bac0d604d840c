#include "service/server/arm_driver/arm_command.h"

#include <drake/lcmt_iiwa_command.hpp>
#include <drake/lcmt_panda_command.hpp>

#include <cmath>

#include "service/server/arm_driver/drake_command_decode.h"

namespace contactsim {
namespace {

// An array sent exactly when its mode bit is set.
Status CheckModeArray(int mode, int bit, const std::vector<double>& values, const char* field) {
  const bool set = (mode & bit) != 0;
  if (set == !values.empty()) return CheckFiniteArray(values, field);
  return Status::InvalidArgument("control_mode_expected " + std::to_string(mode) + (set ? " asks for " : " excludes ") +
                                 field + " (mode bit " + std::to_string(bit) + "), but it has " +
                                 std::to_string(values.size()) + " entries");
}

}  // namespace

Status DecodeIiwaCommand(const void* data, int size, ArmCommand* out) {
  return DecodeDrakeCommand<drake::lcmt_iiwa_command>(data, size, kMaxArmCommandBytes, "lcmt_iiwa_command", &out->utime,
                                                       [&](auto& m) {
    Status st = CheckFiniteArray(m.joint_position, "joint_position");
    if (st.ok()) st = CheckFiniteArray(m.joint_torque, "joint_torque");
    if (!st.ok()) return st;
    out->position = std::move(m.joint_position);
    out->velocity.clear();
    out->torque = std::move(m.joint_torque);
    return Status::Ok();
  });
}

Status DecodePandaCommand(const void* data, int size, ArmCommand* out) {
  return DecodeDrakeCommand<drake::lcmt_panda_command>(data, size, kMaxArmCommandBytes, "lcmt_panda_command",
                                                        &out->utime, [&](auto& m) {
    const int mode = m.control_mode_expected;
    constexpr int kAll = kPandaPositionMode | kPandaVelocityMode | kPandaTorqueMode;
    if (mode <= 0 || (mode & ~kAll) != 0) {
      return Status::InvalidArgument("control_mode_expected " + std::to_string(mode) +
                                     " is not a control mode: give a non-empty OR of position (1), velocity (2) "
                                     "and torque (4)");
    }
    Status st = CheckModeArray(mode, kPandaPositionMode, m.joint_position, "joint_position");
    if (st.ok()) st = CheckModeArray(mode, kPandaVelocityMode, m.joint_velocity, "joint_velocity");
    if (st.ok()) st = CheckModeArray(mode, kPandaTorqueMode, m.joint_torque, "joint_torque");
    if (!st.ok()) return st;
    out->position = std::move(m.joint_position);
    out->velocity = std::move(m.joint_velocity);
    out->torque = std::move(m.joint_torque);
    return Status::Ok();
  });
}

}  // namespace contactsim
