// The server config's wsg_driver block (service/proto/config.proto): which
// model's two fingers answer Drake's Schunk WSG gripper protocol, on which
// channels, at which status rate and with which finger drive gains
// (docs/configuration.md, "WSG gripper driver"; docs/actuators.md, "Drake's
// Schunk WSG gripper").
#pragma once

#include <optional>
#include <string>

#include "service/physics/status.h"
#include "service/proto/config.pb.h"

namespace contactsim {

struct WsgDriverConfig {
  std::string model;                // name of the loaded model
  std::string finger_joints[2];     // its two prismatic finger joints
  std::string command_channel;      // full LCM channel name, no server prefix
  std::string status_channel;
  double status_rate_hz = 0;        // status messages per second of simulated time
  double kp = 0;                    // N/m, each finger's drive
  double kd = 0;                    // N s/m
  std::optional<proto::SceneModel> load;  // a model file to load at start
};

// Drake's channels (SchunkWsgDriver) and status period
// (kSchunkWsgLcmStatusPeriod = 0.05 s in manipulation/schunk_wsg).
constexpr const char* kDefaultWsgCommandChannel = "SCHUNK_WSG_COMMAND";
constexpr const char* kDefaultWsgStatusChannel = "SCHUNK_WSG_STATUS";
constexpr double kDefaultWsgStatusRateHz = 20;
// kp is that of Drake's SchunkWsgDriver (pid_gains kp = 7200), which its
// SchunkWsgPdController applies to the separation's error; driving each
// finger to half the separation with the same kp gives each finger the same
// force for the same error: f = (kp / 2)(2 e) = kp e. Drake's kd is 5, but
// Drake bounds the fingers' speed by moving the target along a trapezoid of
// at most 0.42 m/s (SchunkWsgPositionCommandInterpolator), which the driver
// here, keeping no state outside the world, does not; the damping bounds it
// instead: a finger moves at most at kp e / kd, 1 m/s over the whole
// 55 mm stroke of a WSG 50, and settles with a time constant of kd / kp =
// 56 ms. At a stall the damping exerts nothing, so the grip still reaches
// the force limit. (With kd = 5 a finger closing at its 80 N limit reaches
// 5 m/s, and light boxes are squeezed out of the fingers under lcp.)
constexpr double kDefaultWsgKp = 7200;  // N/m
constexpr double kDefaultWsgKd = 400;   // N s/m
// The grip force before the first command: the initial_force of Drake's
// SchunkWsgCommandReceiver and default_force_limit of its sender.
constexpr double kDefaultWsgForce = 40;  // N

// Checks the block and fills *out, absent fields taking the defaults above.
// On a bad value returns InvalidArgument and names the block's field in
// *field. server_prefix is the server's channel prefix: the driver's
// channels must not be among the server's own <prefix>_* channels.
Status ReadWsgDriverConfig(const proto::WsgDriver& block, const std::string& server_prefix, WsgDriverConfig* out,
                           std::string* field);

}  // namespace contactsim
