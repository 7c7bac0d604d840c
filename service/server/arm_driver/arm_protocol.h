// What differs between Drake's arm-driver protocols, the iiwa's and the
// Panda's: the messages, the default channels and the status rate. The rest
// of the driver (arm_driver.h: the drives, the hold, the readings, the
// gravity compensation) is the same for both.
#pragma once

#include <string>

#include "service/physics/status.h"
#include "service/server/arm_driver/arm_command.h"
#include "service/server/arm_driver/arm_readings.h"

namespace contactsim {

class Publisher;

struct ArmProtocol {
  const char* name;              // the config's protocol: "iiwa" or "panda"
  const char* channel_prefix;    // Drake's channels: <prefix>_COMMAND, <prefix>_STATUS
  const char* command_type;      // the LCM type on the command channel, for logs
  const char* status_type;
  double default_status_rate_hz; // that of Drake's driver for the arm
  // Decodes one command (arm_command.h).
  Status (*decode_command)(const void* data, int size, ArmCommand* out);
  // Builds the status of `readings` at sim_time_s and publishes it on `channel`.
  Status (*publish_status)(const Publisher& publisher, const std::string& channel, double sim_time_s,
                           const ArmJointReadings& readings);
};

// The protocol named `name`, or null.
const ArmProtocol* FindArmProtocol(const std::string& name);
// The names, for an error message: "\"iiwa\" or \"panda\"".
std::string ArmProtocolNames();

}  // namespace contactsim
