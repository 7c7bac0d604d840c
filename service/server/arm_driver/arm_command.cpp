#include "service/server/arm_driver/arm_command.h"

#include <contactsim/wire_check.hpp>
#include <drake/lcmt_iiwa_command.hpp>
#include <drake/lcmt_panda_command.hpp>

#include <cmath>
#include <exception>
#include <new>

namespace contactsim {
namespace {

Status CheckFinite(const std::vector<double>& values, const char* field) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return Status::InvalidArgument(std::string(field) + "[" + std::to_string(i) + "] is " +
                                     std::to_string(values[i]) + ", not a finite number");
    }
  }
  return Status::Ok();
}

// The steps both protocols share: the size limit, the wire check, the
// generated decoder caught, then `read` on the decoded message, which fills
// *out's utime first and returns the protocol's own checks.
template <typename Msg, typename Read>
Status DecodeDrakeCommand(const void* data, int size, const char* type, ArmCommand* out, Read read) {
  const std::string what = std::string(type) + " payload of " + std::to_string(size) + " bytes";
  if (size > kMaxArmCommandBytes) {
    return Status::ResourceExhausted(what + " exceeds the limit of " + std::to_string(kMaxArmCommandBytes) + " bytes");
  }
  std::string why;
  if (data == nullptr || !wire::Check<Msg>(data, size, &why)) {
    return Status::DecodeError("undecodable " + what + ": " + why);
  }
  try {
    Msg m;
    if (m.decode(data, 0, size) != size) return Status::DecodeError("undecodable " + what);
    out->utime = m.utime;
    return read(m);
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted(what + ": out of memory while decoding");
  } catch (const std::exception& e) {
    return Status::DecodeError(what + ": " + e.what());
  }
}

// An array sent exactly when its mode bit is set.
Status CheckModeArray(int mode, int bit, const std::vector<double>& values, const char* field) {
  const bool set = (mode & bit) != 0;
  if (set == !values.empty()) return CheckFinite(values, field);
  return Status::InvalidArgument("control_mode_expected " + std::to_string(mode) + (set ? " asks for " : " excludes ") +
                                 field + " (mode bit " + std::to_string(bit) + "), but it has " +
                                 std::to_string(values.size()) + " entries");
}

}  // namespace

Status DecodeIiwaCommand(const void* data, int size, ArmCommand* out) {
  return DecodeDrakeCommand<drake::lcmt_iiwa_command>(data, size, "lcmt_iiwa_command", out, [&](auto& m) {
    Status st = CheckFinite(m.joint_position, "joint_position");
    if (st.ok()) st = CheckFinite(m.joint_torque, "joint_torque");
    if (!st.ok()) return st;
    out->position = std::move(m.joint_position);
    out->velocity.clear();
    out->torque = std::move(m.joint_torque);
    return Status::Ok();
  });
}

Status DecodePandaCommand(const void* data, int size, ArmCommand* out) {
  return DecodeDrakeCommand<drake::lcmt_panda_command>(data, size, "lcmt_panda_command", out, [&](auto& m) {
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
