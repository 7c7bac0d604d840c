// The server config's arm_driver block (service/proto/config.proto): which
// model answers Drake's arm-driver protocol, on which channels, at which
// status rate and with which drive gains (docs/configuration.md, "Arm
// driver"; docs/actuators.md, "Drake's arm driver").
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "service/physics/status.h"
#include "service/proto/config.pb.h"

namespace contactsim {

struct ArmDriverConfig {
  std::string protocol;         // "iiwa" (lcmt_iiwa_*) or "panda" (lcmt_panda_*)
  std::string model;            // name of the loaded model driven
  std::string command_channel;  // full LCM channel name, no server prefix
  std::string status_channel;
  double status_rate_hz = 0;    // status messages per second of simulated time
  std::vector<double> kp;       // N m/rad, one per joint (a single value is spread)
  std::vector<double> kd;       // N m s/rad, likewise
  bool gravity_compensation = true;
  std::optional<proto::SceneModel> load;  // a model file to load at start
};

// Both of Drake's arms, the iiwa and the Panda, have seven joints.
constexpr int kArmJoints = 7;
// The drives' default gains (docs/actuators.md, "Drake's arm driver"):
// with the arm's weight compensated they only track, lagging a moving
// target by kd / kp = 20 ms, and damp the iiwa's heaviest joint
// (about 1.5 kg m^2) at 0.8 of critical; the implicit drive keeps the light
// wrist, overdamped, stable at any step.
constexpr double kDefaultArmKp = 10000;  // N m/rad
constexpr double kDefaultArmKd = 200;    // N m s/rad

// The protocol's default channel names, those of Drake's drivers:
// IIWA_COMMAND / IIWA_STATUS and PANDA_COMMAND / PANDA_STATUS.
std::string DefaultArmCommandChannel(const std::string& protocol);
std::string DefaultArmStatusChannel(const std::string& protocol);

// Checks the block and fills *out, absent fields taking Drake's defaults (the
// channels above, the status rate of Drake's driver: 200 Hz for the iiwa,
// 1 kHz for the Panda) and
// the gains kDefaultArmKp and kDefaultArmKd. On
// a bad value returns InvalidArgument and names the block's field in *field.
// server_prefix is the server's channel prefix: the driver's channels must
// not be among the server's own <prefix>_* channels.
Status ReadArmDriverConfig(const proto::ArmDriver& block, const std::string& server_prefix, ArmDriverConfig* out,
                           std::string* field);

}  // namespace contactsim
