#include "service/server/arm_driver/wsg_driver_config.h"

#include <cmath>

#include "service/server/arm_driver/driver_config_checks.h"

namespace contactsim {
namespace {

Status ReadGain(bool has, double given, double fallback, const char* name, double* out, std::string* field) {
  *out = has ? given : fallback;
  if (std::isfinite(*out) && *out >= 0) return Status::Ok();
  *field = name;
  return Status::InvalidArgument(std::string(name) + " must be finite and >= 0, got " + std::to_string(*out));
}

}  // namespace

Status ReadWsgDriverConfig(const proto::WsgDriver& block, const std::string& server_prefix, WsgDriverConfig* out,
                           std::string* field) {
  WsgDriverConfig c;
  c.model = block.model();
  if (c.model.empty()) {
    *field = "model";
    return Status::InvalidArgument("model must name the loaded model whose fingers the driver moves");
  }
  if (block.finger_joints_size() != 2 || block.finger_joints(0).empty() || block.finger_joints(1).empty() ||
      block.finger_joints(0) == block.finger_joints(1)) {
    *field = "finger_joints";
    return Status::InvalidArgument("finger_joints must name the two fingers' prismatic joints, two different "
                                   "names; got " + std::to_string(block.finger_joints_size()) + " names");
  }
  c.finger_joints[0] = block.finger_joints(0);
  c.finger_joints[1] = block.finger_joints(1);
  c.command_channel = block.has_command_channel() ? block.command_channel() : kDefaultWsgCommandChannel;
  c.status_channel = block.has_status_channel() ? block.status_channel() : kDefaultWsgStatusChannel;
  Status st = CheckDriverChannels(c.command_channel, c.status_channel, server_prefix, field);
  if (!st.ok()) return st;
  c.status_rate_hz = block.has_status_rate_hz() ? block.status_rate_hz() : kDefaultWsgStatusRateHz;
  if (!(st = CheckDriverStatusRate(c.status_rate_hz, field)).ok()) return st;
  if (!(st = ReadGain(block.has_kp(), block.kp(), kDefaultWsgKp, "kp", &c.kp, field)).ok()) return st;
  if (!(st = ReadGain(block.has_kd(), block.kd(), kDefaultWsgKd, "kd", &c.kd, field)).ok()) return st;
  if (!(st = ReadDriverLoad(block.has_load(), block.load(), c.model, &c.load, field)).ok()) return st;
  *out = c;
  return Status::Ok();
}

}  // namespace contactsim
