#include "service/server/arm_driver/arm_driver_config.h"

#include <cmath>

#include "service/server/arm_driver/arm_protocol.h"
#include "service/server/arm_driver/driver_config_checks.h"

namespace contactsim {
namespace {

std::string ProtocolPrefix(const std::string& protocol) {
  const ArmProtocol* p = FindArmProtocol(protocol);
  return p != nullptr ? p->channel_prefix : "";
}

// kp or kd: none (the default), one for every joint, or one per joint; each
// finite and >= 0.
Status ReadGains(const google::protobuf::RepeatedField<double>& given, double fallback, const char* name,
                 std::vector<double>* out) {
  if (given.size() != 0 && given.size() != 1 && given.size() != kArmJoints) {
    return Status::InvalidArgument(std::string(name) + " has " + std::to_string(given.size()) +
                                   " values; give none, one for every joint, or one per joint (" +
                                   std::to_string(kArmJoints) + ")");
  }
  for (int i = 0; i < given.size(); ++i) {
    if (!std::isfinite(given[i]) || given[i] < 0) {
      return Status::InvalidArgument(std::string(name) + "[" + std::to_string(i) + "] must be finite and >= 0, got " +
                                     std::to_string(given[i]));
    }
  }
  out->assign(kArmJoints, given.empty() ? fallback : given[0]);
  if (given.size() == kArmJoints) out->assign(given.begin(), given.end());
  return Status::Ok();
}

}  // namespace

std::string DefaultArmCommandChannel(const std::string& protocol) { return ProtocolPrefix(protocol) + "_COMMAND"; }
std::string DefaultArmStatusChannel(const std::string& protocol) { return ProtocolPrefix(protocol) + "_STATUS"; }

Status ReadArmDriverConfig(const proto::ArmDriver& block, const std::string& server_prefix, ArmDriverConfig* out,
                           std::string* field) {
  ArmDriverConfig c;
  c.protocol = block.protocol();
  const ArmProtocol* protocol = FindArmProtocol(c.protocol);
  if (protocol == nullptr) {
    *field = "protocol";
    return Status::InvalidArgument("protocol must be " + ArmProtocolNames() + ", got \"" + c.protocol + "\"");
  }
  c.model = block.model();
  if (c.model.empty()) {
    *field = "model";
    return Status::InvalidArgument("model must name the loaded model the driver moves");
  }
  c.command_channel = block.has_command_channel() ? block.command_channel() : DefaultArmCommandChannel(c.protocol);
  c.status_channel = block.has_status_channel() ? block.status_channel() : DefaultArmStatusChannel(c.protocol);
  Status st = CheckDriverChannels(c.command_channel, c.status_channel, server_prefix, field);
  if (!st.ok()) return st;
  c.status_rate_hz = block.has_status_rate_hz() ? block.status_rate_hz() : protocol->default_status_rate_hz;
  if (!(st = CheckDriverStatusRate(c.status_rate_hz, field)).ok()) return st;
  if (!(st = ReadGains(block.kp(), kDefaultArmKp, "kp", &c.kp)).ok()) {
    *field = "kp";
    return st;
  }
  if (!(st = ReadGains(block.kd(), kDefaultArmKd, "kd", &c.kd)).ok()) {
    *field = "kd";
    return st;
  }
  c.gravity_compensation = !block.has_gravity_compensation() || block.gravity_compensation();
  if (!(st = ReadDriverLoad(block.has_load(), block.load(), c.model, &c.load, field)).ok()) return st;
  *out = c;
  return Status::Ok();
}

}  // namespace contactsim
