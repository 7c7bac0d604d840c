#include "service/server/arm_driver/driver_config_checks.h"

#include <cmath>

namespace contactsim {
namespace {

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
    return Status::InvalidArgument(std::string(which) +
                                   " must be 1 to 255 printable characters without spaces, got \"" + name + "\"");
  }
  if (name.rfind(server_prefix + "_", 0) == 0) {
    return Status::InvalidArgument(std::string(which) + " \"" + name + "\" is among the server's own channels (" +
                                   server_prefix + "_*); choose a name outside them");
  }
  return Status::Ok();
}

}  // namespace

Status CheckDriverChannels(const std::string& command_channel, const std::string& status_channel,
                           const std::string& server_prefix, std::string* field) {
  Status st = CheckChannel(command_channel, server_prefix, "command_channel");
  if (!st.ok()) {
    *field = "command_channel";
    return st;
  }
  if (!(st = CheckChannel(status_channel, server_prefix, "status_channel")).ok()) {
    *field = "status_channel";
    return st;
  }
  if (status_channel == command_channel) {
    *field = "status_channel";
    return Status::InvalidArgument("status_channel and command_channel are both \"" + status_channel +
                                   "\"; the driver's status and its commands need channels of their own");
  }
  return Status::Ok();
}

Status CheckDriverStatusRate(double rate_hz, std::string* field) {
  if (std::isfinite(rate_hz) && rate_hz > 0 && rate_hz <= kMaxDriverStatusRateHz) return Status::Ok();
  *field = "status_rate_hz";
  return Status::InvalidArgument("status_rate_hz must be in (0, 1000] Hz, got " + std::to_string(rate_hz));
}

Status ReadDriverLoad(bool has_load, const proto::SceneModel& load, const std::string& model,
                      std::optional<proto::SceneModel>* out, std::string* field) {
  out->reset();
  if (!has_load) return Status::Ok();
  if (load.path().empty()) {
    *field = "load";
    return Status::InvalidArgument("load.path must name the model file to load");
  }
  if (!load.name().empty() && load.name() != model) {
    *field = "load";
    return Status::InvalidArgument("load.name \"" + load.name() + "\" differs from model \"" + model +
                                   "\"; leave it out or give the same name");
  }
  *out = load;
  (*out)->set_name(model);
  return Status::Ok();
}

}  // namespace contactsim
