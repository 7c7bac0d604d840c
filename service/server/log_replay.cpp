#include "service/server/log_replay.h"

#include <contactsim/protocol.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/signature.h>
#include <contactsim/state_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <cinttypes>
#include <cstdio>

#include "service/server/arm_driver/driver_commands.h"
#include "service/server/server_config.h"

namespace contactsim {
namespace {

std::string Hex(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof(buf), "%016" PRIx64, v);
  return buf;
}

// Where a replay publishes: nowhere. Its replies and STATEs are not needed;
// the replayer reads the world directly.
class NullTransport : public Transport {
 public:
  void Publish(const std::string&, const void*, int) override {}
};

}  // namespace

std::string ReplayReport::Summary() const {
  std::string s;
  if (diverged) {
    s += "divergence at step " + std::to_string(divergent_step) + ": logged state_hash " + Hex(logged_hash) +
         ", replayed " + Hex(replayed_hash);
    if (replayed_step != divergent_step) s += " (the replay is at step " + std::to_string(replayed_step) + ")";
    s += "\n";
    if (logged_digest != replayed_digest) {
      s += "  the step's lockstep inputs differ too: logged input_digest " + Hex(logged_digest) + ", replayed " +
           Hex(replayed_digest) + "\n";
    }
    s += "  last command fed before it: " + (last_command.empty() ? std::string("none") : last_command) + "\n";
  } else {
    s += "identical: " + std::to_string(states_compared) + " STATE messages";
    if (states_compared > 0) s += " (steps " + std::to_string(first_step) + " to " + std::to_string(last_step) + ")";
    s += " match the replay\n";
  }
  if (states_undecodable > 0) {
    s += "error: " + std::to_string(states_undecodable) +
         " STATE messages are not this build's state_t (its fingerprint or layout differs: a log recorded by "
         "another version of contactsim) and were not compared; replay the log with the version that recorded it\n";
  }
  s += "  " + std::to_string(commands_fed) + " commands and " + std::to_string(inputs_fed) + " lockstep inputs fed";
  if (unanswered > 0) s += "; " + std::to_string(unanswered) + " commands had no reply in the log and were not fed";
  s += "\n";
  return s;
}

LogReplayer::LogReplayer(SimServer* server)
    : server_(server), reply_(server->Channel(protocol::kReply)), state_(server->Channel(protocol::kState)) {
  for (const CommandChannel& c : CommandChannels()) channels_[server->Channel(c.suffix)] = &c;
  const ServerOptions& options = server->options();
  if (options.arm_driver) drivers_[options.arm_driver->command_channel] = RecordKind::kArmCommand;
  if (options.wsg_driver) drivers_[options.wsg_driver->command_channel] = RecordKind::kWsgCommand;
}

bool LogReplayer::OnEvent(const std::string& channel, const void* data, int size) {
  if (report_.diverged) return false;
  const auto it = channels_.find(channel);
  const auto driver = drivers_.find(channel);
  if (it != channels_.end()) {
    OnCommand(channel, *it->second, data, size);
  } else if (driver != drivers_.end()) {
    OnDriverCommand(channel, driver->second, data, size);
  } else if (channel == reply_) {
    OnReply(data, size);
  } else if (channel == state_) {
    OnState(data, size);
  }
  return !report_.diverged;
}

void LogReplayer::OnCommand(const std::string& channel_name, const CommandChannel& channel, const void* data,
                            int size) {
  if (!channel.replied) {
    // accepted inputs get no reply: queued now, applied at their step
    server_->OnMessage(channel_name, data, size);
    server_->ApplyInbox();
    ++report_.inputs_fed;
    return;
  }
  Command header;
  const Status st = channel.decode(data, UnsignedSize(data, size), DecodeContext{}, &header);
  // an undecodable command changed nothing live (DECODE_ERROR): nothing to feed
  if (st.code() == StatusCode::kDecodeError) return;
  pending_[{header.client_id, header.request_id}].push_back(
      {channel_name, channel.suffix, std::string(static_cast<const char*>(data), size)});
}

void LogReplayer::OnDriverCommand(const std::string& channel_name, RecordKind record, const void* data, int size) {
  const ServerOptions& options = server_->options();
  const ArmProtocol* arm = options.arm_driver ? FindArmProtocol(options.arm_driver->protocol) : nullptr;
  Command cmd;
  int64_t utime = -1;
  const Status st = DecodeDriverCommand(record, arm, data, size, &cmd, &utime);
  // the live server answered an undecodable one with an error, or not at
  // all: nothing to feed
  if (utime < 0 && !st.ok()) return;
  pending_[{channel_name, utime}].push_back(
      {channel_name, channel_name, std::string(static_cast<const char*>(data), size)});
}

void LogReplayer::OnReply(const void* data, int size) {
  reply_t r;
  if (r.decode(data, 0, size) < 0) return;
  auto it = pending_.find({r.client_id, r.request_id});
  if (it == pending_.end()) return;  // an input's error reply, or a command sent before the log began
  const Pending p = std::move(it->second.front());
  it->second.pop_front();
  if (it->second.empty()) pending_.erase(it);
  // a refused command changed nothing live (some refusals, such as a rate
  // limit, depend on the wall clock and would not repeat here)
  if (r.code != reply_t::OK) return;
  // the live world was at reply.step when the command applied
  StepTo(r.step);
  server_->OnMessage(p.channel, p.payload.data(), static_cast<int>(p.payload.size()));
  server_->ApplyInbox();
  ++report_.commands_fed;
  report_.last_command = p.label + " from \"" + r.client_id + "\" #" + std::to_string(r.request_id) +
                         " at step " + std::to_string(r.step) + " (" + r.message + ")";
}

void LogReplayer::StepTo(int64_t step) {
  while (server_->world().step < step) server_->StepOnce();
}

void LogReplayer::OnState(const void* data, int size) {
  state_t m;
  if (m.decode(data, 0, size) < 0) {
    ++report_.states_undecodable;
    return;
  }
  StepTo(m.step);
  const uint64_t logged = static_cast<uint64_t>(m.state_hash);
  const uint64_t replayed = HashWorldState(server_->world());
  const uint64_t logged_digest = static_cast<uint64_t>(m.input_digest);
  if (server_->world().step != m.step || logged != replayed || logged_digest != server_->input_digest()) {
    report_.diverged = true;
    report_.divergent_step = m.step;
    report_.replayed_step = server_->world().step;
    report_.logged_hash = logged;
    report_.replayed_hash = replayed;
    report_.logged_digest = logged_digest;
    report_.replayed_digest = server_->input_digest();
    return;
  }
  if (report_.first_step < 0) report_.first_step = m.step;
  report_.last_step = m.step;
  ++report_.states_compared;
}

const ReplayReport& LogReplayer::Finish() {
  report_.unanswered = 0;
  for (const auto& [key, waiting] : pending_) report_.unanswered += static_cast<int64_t>(waiting.size());
  return report_;
}

Status ReplayLogFile(const std::string& path, LogReplayer* replayer) {
  lcm::LogFile log(path, "r");
  if (!log.good()) return Status::NotFound("--replay: cannot read the LCM log " + path);
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    if (!replayer->OnEvent(e->channel, e->data, e->datalen)) break;
  }
  return Status::Ok();
}

int RunReplay(ServerSetup setup, const std::string& log_path) {
  // a replay reads: no journal to recover from or write, no snapshot files
  setup.options.journal_dir.clear();
  setup.options.write_files = false;
  setup.options.live_line = false;
  // the log holds only what the live server admitted; refusals are skipped,
  // and signatures were checked live (their seqs are stale now): without a
  // key the server cuts the trailers off
  setup.options.max_commands_per_second = 0.0;
  setup.options.auth_key.clear();
  NullTransport transport;
  SimServer server(setup.options, &transport);
  Status st = server.Init(setup.scene.get(), setup.method);
  LogReplayer replayer(&server);
  if (st.ok()) st = ReplayLogFile(log_path, &replayer);
  if (!st.ok()) {
    spdlog::critical("{}", st.message());
    return 1;
  }
  const ReplayReport& report = replayer.Finish();
  std::fputs(report.Summary().c_str(), stdout);
  std::fflush(stdout);
  if (report.diverged) return 2;
  return report.states_undecodable > 0 ? 1 : 0;
}

}  // namespace contactsim
