#include "service/server/log_replay.h"

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/state_t.hpp>
#include <lcm/lcm-cpp.hpp>
#include <spdlog/spdlog.h>

#include <cinttypes>
#include <cstdio>

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

// The (client id, request id) of a command payload; false if undecodable.
template <typename Msg>
bool Header(const void* data, int size, std::string* client_id, int64_t* request_id) {
  Msg m;
  if (m.decode(data, 0, size) < 0) return false;
  *client_id = m.client_id;
  *request_id = m.request_id;
  return true;
}

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
  s += "  " + std::to_string(commands_fed) + " commands and " + std::to_string(inputs_fed) + " lockstep inputs fed";
  if (unanswered > 0) s += "; " + std::to_string(unanswered) + " commands had no reply in the log and were not fed";
  s += "\n";
  return s;
}

LogReplayer::LogReplayer(SimServer* server)
    : server_(server),
      body_(server->Channel("BODY_CMD")),
      scene_(server->Channel("SCENE_CMD")),
      joint_(server->Channel("JOINT_CMD")),
      input_(server->Channel("INPUT")),
      reply_(server->Channel("REPLY")),
      state_(server->Channel("STATE")) {}

bool LogReplayer::OnEvent(const std::string& channel, const void* data, int size) {
  if (report_.diverged) return false;
  std::string cid;
  int64_t rid = 0;
  if (channel == body_) {
    if (Header<body_cmd_t>(data, size, &cid, &rid)) OnCommand(Source::kBody, cid, rid, data, size);
  } else if (channel == scene_) {
    if (Header<scene_cmd_t>(data, size, &cid, &rid)) OnCommand(Source::kScene, cid, rid, data, size);
  } else if (channel == joint_) {
    if (Header<joint_cmd_t>(data, size, &cid, &rid)) OnCommand(Source::kJoint, cid, rid, data, size);
  } else if (channel == input_) {
    // accepted inputs get no reply: queued now, applied at their step
    server_->OnInputMessage(data, size);
    server_->ApplyInbox();
    ++report_.inputs_fed;
  } else if (channel == reply_) {
    OnReply(data, size);
  } else if (channel == state_) {
    OnState(data, size);
  }
  // an undecodable command changed nothing live (DECODE_ERROR): nothing to feed
  return !report_.diverged;
}

void LogReplayer::OnCommand(Source source, const std::string& client_id, int64_t request_id, const void* data,
                            int size) {
  pending_[{client_id, request_id}] = {source, std::string(static_cast<const char*>(data), size)};
}

void LogReplayer::OnReply(const void* data, int size) {
  reply_t r;
  if (r.decode(data, 0, size) < 0) return;
  auto it = pending_.find({r.client_id, r.request_id});
  if (it == pending_.end()) return;  // an input's error reply, or a command sent before the log began
  // the live world was at reply.step when the command applied
  StepTo(r.step);
  Feed(it->second.source, it->second.payload);
  report_.last_command = std::string(it->second.source == Source::kBody    ? "BODY_CMD"
                                     : it->second.source == Source::kScene ? "SCENE_CMD"
                                                                           : "JOINT_CMD") +
                         " from \"" + r.client_id + "\" #" + std::to_string(r.request_id) + " at step " +
                         std::to_string(r.step) + " (" + r.message + ")";
  pending_.erase(it);
}

void LogReplayer::Feed(Source source, const std::string& payload) {
  const int n = static_cast<int>(payload.size());
  switch (source) {
    case Source::kBody: server_->OnBodyMessage(payload.data(), n); break;
    case Source::kScene: server_->OnSceneMessage(payload.data(), n); break;
    case Source::kJoint: server_->OnJointMessage(payload.data(), n); break;
  }
  server_->ApplyInbox();
  ++report_.commands_fed;
}

void LogReplayer::StepTo(int64_t step) {
  while (server_->world().step < step) server_->StepOnce();
}

void LogReplayer::OnState(const void* data, int size) {
  state_t m;
  if (m.decode(data, 0, size) < 0) return;
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
  report_.unanswered = static_cast<int64_t>(pending_.size());
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
  return report.diverged ? 2 : 0;
}

}  // namespace contactsim
