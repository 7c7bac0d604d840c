#include "service/server/arm_driver/arm_command.h"

#include <contactsim/wire_check.hpp>
#include <drake/lcmt_iiwa_command.hpp>

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

}  // namespace

Status DecodeIiwaCommand(const void* data, int size, ArmCommand* out) {
  const std::string what = "lcmt_iiwa_command payload of " + std::to_string(size) + " bytes";
  if (size > kMaxArmCommandBytes) {
    return Status::ResourceExhausted(what + " exceeds the limit of " + std::to_string(kMaxArmCommandBytes) + " bytes");
  }
  std::string why;
  if (data == nullptr || !wire::Check<drake::lcmt_iiwa_command>(data, size, &why)) {
    return Status::DecodeError("undecodable " + what + ": " + why);
  }
  try {
    drake::lcmt_iiwa_command m;
    if (m.decode(data, 0, size) != size) return Status::DecodeError("undecodable " + what);
    out->utime = m.utime;
    Status st = CheckFinite(m.joint_position, "joint_position");
    if (st.ok()) st = CheckFinite(m.joint_torque, "joint_torque");
    if (!st.ok()) return st;
    out->position = std::move(m.joint_position);
    out->torque = std::move(m.joint_torque);
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted(what + ": out of memory while decoding");
  } catch (const std::exception& e) {
    return Status::DecodeError(what + ": " + e.what());
  }
}

}  // namespace contactsim
