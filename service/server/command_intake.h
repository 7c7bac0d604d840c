// The LCM thread's side of the server: a payload on a command channel
// (command_channels.h) has its signature checked before anything is decoded,
// is decoded and checked without the world, its sender admitted against the
// rate limit, and is queued in the batch's inbox or answered at once.
// Everything here belongs to the LCM thread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "service/server/arm_driver/arm_protocol.h"
#include "service/server/command_auth.h"
#include "service/server/command_batch.h"
#include "service/server/command_channels.h"
#include "service/server/rate_limiter.h"
#include "service/server/server_options.h"

namespace contactsim {

class CommandIntake {
 public:
  CommandIntake(const ServerOptions& options, CommandBatch* batch);

  // One payload received on `channel`; a command channel's is queued or
  // answered, anything else ignored. Never throws.
  void OnMessage(const std::string& channel, const void* data, int size);
  // The full names of the command channels, to subscribe to.
  std::vector<std::string> ChannelNames() const;

 private:
  // Asked by a channel's decoder once the sender is known, before the
  // command's own checks (a LOAD_SCENE reads a file): commands beyond a
  // client's rate are refused unread.
  Status AdmitClient(const CommandChannel& channel, const std::string& client_id);
  // A command on a driver's channel (arm_driver/: the arm's or the WSG
  // gripper's): Drake's messages carry no sender, signature or request id,
  // so it is named by the channel and its utime, and bounded by the inbox
  // rather than a rate. `record` says whose (arm_driver/driver_commands.h).
  void OnDriverCommand(const std::string& channel, const void* data, int size, RecordKind record);

  const std::string prefix_;  // "<prefix>_"
  const std::string arm_channel_;  // the arm driver's command channel; "" without one
  const ArmProtocol* arm_protocol_;  // its protocol; null without one
  const std::string wsg_channel_;  // the WSG driver's command channel; "" without one
  const double max_commands_per_second_, command_burst_;
  DecodeContext decode_context_;  // new bodies get the default Material
  RateLimiter rate_limiter_;
  std::unique_ptr<CommandAuthenticator> auth_;  // null without a key
  CommandBatch* batch_;
};

}  // namespace contactsim
