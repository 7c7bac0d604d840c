// The checks every driver block of the server config shares (arm_driver,
// wsg_driver: arm_driver_config.h, wsg_driver_config.h): the two channels,
// the status rate and the model file loaded at start. Each returns
// InvalidArgument with the message naming the value, and sets *field to the
// block's field at fault.
#pragma once

#include <optional>
#include <string>

#include "service/physics/status.h"
#include "service/proto/config.pb.h"

namespace contactsim {

// A faster rate than one message per millisecond is more than any arm or
// gripper interface offers (the KUKA FRI and the Franka control loop both
// run at 1 kHz at most, the WSG's firmware at 20 Hz).
constexpr double kMaxDriverStatusRateHz = 1000;

// Both channels printable without spaces, 1 to 255 characters, outside the
// server's own <server_prefix>_* channels, and different from each other.
Status CheckDriverChannels(const std::string& command_channel, const std::string& status_channel,
                           const std::string& server_prefix, std::string* field);

// A rate in (0, kMaxDriverStatusRateHz] Hz.
Status CheckDriverStatusRate(double rate_hz, std::string* field);

// The block's `load`, if given, named `model`: its path set and its name
// empty or `model`.
Status ReadDriverLoad(bool has_load, const proto::SceneModel& load, const std::string& model,
                      std::optional<proto::SceneModel>* out, std::string* field);

}  // namespace contactsim
