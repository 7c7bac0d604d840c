#include "service/server/command_intake.h"

#include "service/physics/validation.h"
#include "service/server/arm_driver/driver_commands.h"

namespace contactsim {

CommandIntake::CommandIntake(const ServerOptions& options, CommandBatch* batch)
    : prefix_(options.prefix + "_"),
      arm_channel_(options.arm_driver ? options.arm_driver->command_channel : ""),
      arm_protocol_(options.arm_driver ? FindArmProtocol(options.arm_driver->protocol) : nullptr),
      wsg_channel_(options.wsg_driver ? options.wsg_driver->command_channel : ""),
      max_commands_per_second_(options.max_commands_per_second),
      command_burst_(options.command_burst),
      rate_limiter_(options.max_commands_per_second, options.command_burst),
      batch_(batch) {
  if (!options.auth_key.empty()) {
    auth_ = std::make_unique<CommandAuthenticator>(options.auth_key, options.auth_window_s);
  }
  decode_context_.limits = options.decode_limits;
  decode_context_.model_paths =
      model::MakeModelPaths(options.model_path_flags, options.model_paths, model::ModelPathEnvironment());
}

std::vector<std::string> CommandIntake::ChannelNames() const {
  std::vector<std::string> names;
  for (const CommandChannel& c : CommandChannels()) names.push_back(prefix_ + c.suffix);
  if (!arm_channel_.empty()) names.push_back(arm_channel_);
  if (!wsg_channel_.empty()) names.push_back(wsg_channel_);
  return names;
}

// Lockstep inputs come at the step rate and are bounded by the inbox instead.
Status CommandIntake::AdmitClient(const CommandChannel& channel, const std::string& client_id) {
  if (!channel.replied || rate_limiter_.Admit(client_id, RateLimiter::Clock::now())) return Status::Ok();
  return Status::ResourceExhausted("client \"" + client_id + "\" exceeds max_commands_per_second = " +
                                   FormatValue(max_commands_per_second_) + " (burst " + FormatValue(command_burst_) +
                                   ")");
}

void CommandIntake::OnDriverCommand(const std::string& channel, const void* data, int size, RecordKind record) {
  Command cmd;
  cmd.client_id = channel;
  cmd.record = record;
  Status st = DecodeDriverCommand(record, arm_protocol_, data, size, &cmd, &cmd.request_id);
  if (st.ok()) {
    cmd.payload.assign(static_cast<const char*>(data), size);
    st = batch_->Enqueue(cmd);
  }
  if (!st.ok()) batch_->Reject(cmd.client_id, cmd.request_id, st, channel.c_str());
}

void CommandIntake::OnMessage(const std::string& channel_name, const void* data, int size) {
  if (!arm_channel_.empty() && channel_name == arm_channel_) {
    return OnDriverCommand(channel_name, data, size, RecordKind::kArmCommand);
  }
  if (!wsg_channel_.empty() && channel_name == wsg_channel_) {
    return OnDriverCommand(channel_name, data, size, RecordKind::kWsgCommand);
  }
  if (channel_name.compare(0, prefix_.size(), prefix_) != 0) return;
  const CommandChannel* channel = ChannelOfSuffix(channel_name.substr(prefix_.size()));
  if (channel == nullptr) return;
  // a signature is checked before anything is decoded; without a key, a
  // trailer a signing client added is cut off unread
  int payload_size = UnsignedSize(data, size);
  uint64_t seq = 0;
  const Status signed_ok = auth_ ? auth_->Admit(channel_name, data, size, &payload_size, &seq) : Status::Ok();
  if (!signed_ok.ok()) payload_size = UnsignedSize(data, size);
  Command cmd;
  cmd.request_id = -1;
  DecodeContext context = decode_context_;
  // asked once the sender is known: a refused signature still names the
  // sender in its reply, but nothing of its command is checked or run
  context.admit = [&](const std::string& client_id) {
    if (!signed_ok.ok()) return signed_ok;
    if (auth_) {
      const Status st = auth_->AcceptSequence(client_id, seq);
      if (!st.ok()) return st;
    }
    return AdmitClient(*channel, client_id);
  };
  Status st = channel->decode(data, payload_size, context, &cmd);
  cmd.record = channel->record;
  if (st.ok()) st = batch_->Enqueue(cmd);
  if (st.ok()) return;
  if (!signed_ok.ok() && st.code() == StatusCode::kDecodeError) st = signed_ok;
  // an undecodable payload has no sender to name
  if (st.code() == StatusCode::kDecodeError) {
    batch_->Reject("", -1, Status::DecodeError(st.message() + " (on " + channel_name + ")"), channel->suffix);
  } else {
    batch_->Reject(cmd.client_id, cmd.request_id, st, channel->suffix);
  }
}

}  // namespace contactsim
