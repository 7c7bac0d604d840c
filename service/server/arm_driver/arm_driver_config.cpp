#include "service/server/arm_driver/arm_driver_config.h"

#include <cmath>

#include "service/server/arm_driver/arm_protocol.h"

namespace contactsim {
namespace {

// A faster rate than one message per millisecond is more than any arm
// interface offers (the KUKA FRI and the Franka control loop both run at
// 1 kHz at most). The default is each protocol's (arm_protocol.cpp).
constexpr double kMaxStatusRateHz = 1000;

std::string ProtocolPrefix(const std::string& protocol) {
  const ArmProtocol* p = FindArmProtocol(protocol);
  return p != nullptr ? p->channel_prefix : "";
}

// An LCM channel name the shell and lcm-spy show as is: printable, no spaces.
bool PlainChannelName(const std::string& name) {
  if (name.empty() || name.size() > 255) return false;
  for (char c : name) {
    if (c <= ' ' || c > '~') return false;
  }
  return true;
}

Status CheckChannel(const std::string& name, const std::string& server_prefix, const char* which) {
  if (!PlainChannelName(name)) {
    return Status::InvalidArgument(std::string(which) + " must be 1 to 255 printable characters without spaces, got \"" +
                                   name + "\"");
  }
  if (name.rfind(server_prefix + "_", 0) == 0) {
    return Status::InvalidArgument(std::string(which) + " \"" + name + "\" is among the server's own channels (" +
                                   server_prefix + "_*); choose a name outside them");
  }
  return Status::Ok();
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
  Status st = CheckChannel(c.command_channel, server_prefix, "command_channel");
  if (!st.ok()) {
    *field = "command_channel";
    return st;
  }
  if (!(st = CheckChannel(c.status_channel, server_prefix, "status_channel")).ok()) {
    *field = "status_channel";
    return st;
  }
  if (c.status_channel == c.command_channel) {
    *field = "status_channel";
    return Status::InvalidArgument("status_channel and command_channel are both \"" + c.status_channel +
                                   "\"; the driver's status and its commands need channels of their own");
  }
  c.status_rate_hz = block.has_status_rate_hz() ? block.status_rate_hz() : protocol->default_status_rate_hz;
  if (!std::isfinite(c.status_rate_hz) || c.status_rate_hz <= 0 || c.status_rate_hz > kMaxStatusRateHz) {
    *field = "status_rate_hz";
    return Status::InvalidArgument("status_rate_hz must be in (0, 1000] Hz, got " + std::to_string(c.status_rate_hz));
  }
  if (!(st = ReadGains(block.kp(), kDefaultArmKp, "kp", &c.kp)).ok()) {
    *field = "kp";
    return st;
  }
  if (!(st = ReadGains(block.kd(), kDefaultArmKd, "kd", &c.kd)).ok()) {
    *field = "kd";
    return st;
  }
  c.gravity_compensation = !block.has_gravity_compensation() || block.gravity_compensation();
  if (block.has_load()) {
    if (block.load().path().empty()) {
      *field = "load";
      return Status::InvalidArgument("load.path must name the model file to load");
    }
    if (!block.load().name().empty() && block.load().name() != c.model) {
      *field = "load";
      return Status::InvalidArgument("load.name \"" + block.load().name() + "\" differs from model \"" + c.model +
                                     "\"; leave it out or give the same name");
    }
    c.load = block.load();
    c.load->set_name(c.model);
  }
  *out = c;
  return Status::Ok();
}

}  // namespace contactsim
