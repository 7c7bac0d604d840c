#include "service/server/sim_server.h"

#include <contactsim/status_t.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>
#include <unistd.h>

#include "service/contact/contact_method_registry.h"
#include "service/contact/method_support.h"
#include "service/physics/validation.h"
#include "service/server/messages.h"

namespace contactsim {

using Clock = std::chrono::steady_clock;

SimServer::SimServer(ServerOptions options, Transport* transport)
    : options_(std::move(options)),
      transport_(transport),
      rate_limiter_(options_.max_commands_per_second, options_.command_burst),
      snapshots_(options_.max_snapshots) {
  if (!options_.auth_key.empty()) {
    auth_ = std::make_unique<CommandAuthenticator>(options_.auth_key, options_.auth_window_s);
  }
  decode_context_.default_material = default_material_;
  decode_context_.limits = options_.decode_limits;
  paused_ = options_.start_paused;
  mode_ = options_.mode;
  real_time_factor_ = options_.real_time_factor;
}

Status SimServer::Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method) {
  Status st = detector_.SetBroadphase(options_.broadphase);
  if (!st.ok()) return st;
  if (!(st = detector_.SetThreads(options_.threads)).ok()) return st;
  if (scene != nullptr) {
    if (!(st = BuildWorld(*scene, &world_)).ok()) return st;
  }
  world_.sleep.enabled = options_.sleep;  // a recovered snapshot brings its own
  // a configured method that cannot honour the configured scene (method_support.h)
  if (!(st = CheckMethodSupports(method->Name(), world_)).ok()) return st;
  method_ = std::move(method);
  if (!(st = Recover()).ok()) return st;
  UpdateRates();
  last_status_wall_ = Clock::now();
  PublishStatus(last_status_wall_);
  PublishState();
  return Status::Ok();
}

// ---- LCM thread -----------------------------------------------------------

std::vector<std::string> SimServer::CommandChannelNames() const {
  std::vector<std::string> names;
  for (const CommandChannel& c : CommandChannels()) names.push_back(Channel(c.suffix));
  return names;
}

void SimServer::CountRejection(const Status& status) {
  ++rejected_;
  if (status.code() == StatusCode::kUnauthenticated) ++unauthenticated_;
  if (status.code() == StatusCode::kResourceExhausted) ++limited_;
  std::lock_guard<std::mutex> lock(mutex_);
  last_error_ = status.message();
}

// An answer before the command reaches the simulation thread (it carries no
// step: the world belongs to that thread).
void SimServer::Reject(const std::string& client_id, int64_t request_id, const Status& status, const char* channel) {
  CountRejection(status);
  spdlog::warn("rejected {} from \"{}\" #{}: {}", channel, client_id, request_id, status.message());
  reply_t r;
  r.client_id = client_id;
  r.request_id = request_id;
  r.code = static_cast<int32_t>(status.code());
  r.message = status.message();
  r.step = -1;
  r.time = 0.0;
  r.num_ids = 0;
  const int n = r.getEncodedSize();
  std::vector<uint8_t> buf(n);
  r.encode(buf.data(), 0, n);
  transport_->Publish(Channel("REPLY"), buf.data(), n);
}

// Called by a channel's decoder once the sender is known, before the
// command's own checks (a LOAD_SCENE reads a file): commands beyond a
// client's rate are refused unread. Lockstep inputs come at the step rate
// and are bounded by the inbox instead.
Status SimServer::AdmitClient(const CommandChannel& channel, const std::string& client_id) {
  if (!channel.replied || rate_limiter_.Admit(client_id, RateLimiter::Clock::now())) return Status::Ok();
  return Status::ResourceExhausted("client \"" + client_id + "\" exceeds max_commands_per_second = " +
                                   FormatValue(options_.max_commands_per_second) + " (burst " +
                                   FormatValue(options_.command_burst) + ")");
}

void SimServer::OnMessage(const std::string& channel_name, const void* data, int size) {
  const std::string prefix = options_.prefix + "_";
  if (channel_name.compare(0, prefix.size(), prefix) != 0) return;
  const CommandChannel* channel = ChannelOfSuffix(channel_name.substr(prefix.size()));
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
  if (st.ok()) st = Enqueue(cmd);
  if (st.ok()) return;
  if (!signed_ok.ok() && st.code() == StatusCode::kDecodeError) st = signed_ok;
  // an undecodable payload has no sender to name
  if (st.code() == StatusCode::kDecodeError) {
    Reject("", -1, Status::DecodeError(st.message() + " (on " + channel_name + ")"), channel->suffix);
  } else {
    Reject(cmd.client_id, cmd.request_id, st, channel->suffix);
  }
}

// Moves `cmd` into the inbox, or leaves it as it was when the inbox is full.
Status SimServer::Enqueue(Command& cmd) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (static_cast<int>(inbox_.size()) >= options_.max_queued_commands) {
      return Status::ResourceExhausted("the server's inbox holds max_queued_commands = " +
                                       std::to_string(options_.max_queued_commands) + " commands; try again");
    }
    inbox_.push_back(std::move(cmd));
  }
  wake_.notify_one();
  return Status::Ok();
}

void SimServer::UpdateRates() {
  auto every = [this](double rate) -> int64_t {
    if (rate <= 0.0) return 1;
    return std::max<int64_t>(1, std::llround(1.0 / (rate * world_.dt)));
  };
  state_every_ = every(options_.state_rate_hz);
  contacts_every_ = every(options_.contacts_rate_hz);
}

void SimServer::CancelStepCommands(const std::string& why) {
  for (const PendingStep& p : pending_steps_) {
    const int64_t done = std::clamp<int64_t>(p.steps - (p.target_step - world_.step), 0, p.steps);
    SendReply(p.client_id, p.request_id,
              Status::FailedPrecondition("step interrupted: " + why + " after " + std::to_string(done) + " of " +
                                         std::to_string(p.steps) + " steps (at step " +
                                         std::to_string(world_.step) + ")"),
              "");
  }
  pending_steps_.clear();
  step_budget_ = 0;
}

void SimServer::SimulateStep() {
  last_stats_ = sleep_.Step(world_, *method_, detector_, &contacts_);
  if (rewinding_) ReportRewindProgress();
}

void SimServer::StepWorld() {
  ApplyInputs();
  SimulateStep();
  if (step_budget_ > 0) --step_budget_;
  if (options_.snapshot_every > 0 && world_.step % options_.snapshot_every == 0) TakePeriodicSnapshot();
  // controllers need every STATE
  if (world_.step % state_every_ == 0 || (mode_ == RunMode::kLockstep && lockstep_.active())) PublishState();
  if (world_.step % contacts_every_ == 0) PublishContacts();
  FinishStepCommands();
  ReportStepProgress(false);
}

// Replies to the STEP commands whose last step is done, after their STATE.
void SimServer::FinishStepCommands() {
  while (!pending_steps_.empty() && pending_steps_.front().target_step <= world_.step) {
    if (last_state_step_ != world_.step) PublishState();
    const PendingStep p = pending_steps_.front();
    pending_steps_.pop_front();
    // recovery brings the world back to the last step a reply acknowledged
    Status st = JournalCommand(RecordKind::kStepTo, "");
    if (st.ok()) st = journal_.Sync();
    if (!st.ok()) st = Status::Internal("steps taken, but a restart would not keep them: " + st.message());
    SendReply(p.client_id, p.request_id, st, "at step " + std::to_string(world_.step));
  }
}

template <typename Msg>
static void PublishMessage(Transport* transport, const std::string& channel, const Msg& msg) {
  const int n = msg.getEncodedSize();
  std::vector<uint8_t> buf(n);
  msg.encode(buf.data(), 0, n);
  transport->Publish(channel, buf.data(), n);
}

void SimServer::PublishState() {
  state_t msg = MakeStateMessage(world_);
  msg.input_digest = static_cast<int64_t>(input_digest_);
  PublishMessage(transport_, Channel("STATE"), msg);
  last_state_step_ = world_.step;
}

void SimServer::PublishContacts() {
  PublishMessage(transport_, Channel("CONTACTS"), MakeContactsMessage(world_, contacts_, *method_));
}

void SimServer::PublishStatus(Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - last_status_wall_).count();
  if (elapsed > 0.0) {
    step_rate_ = (world_.step - last_status_step_) / elapsed;
    measured_rtf_ = (world_.time - last_status_time_) / elapsed;
  }
  last_status_wall_ = now;
  last_status_step_ = world_.step;
  last_status_time_ = world_.time;

  status_t s;
  s.version = CONTACTSIM_VERSION;
  s.mode = static_cast<int8_t>(mode_);  // equal values by design
  s.paused = paused_ && step_budget_ == 0;
  s.method = method_->Name();
  for (const auto& [k, v] : method_->Params()) s.method_params += (s.method_params.empty() ? "" : " ") + k + "=" + v;
  if (const ContactMethodEntry* e = FindContactMethod(method_->Name())) {
    s.method_contract = DescribeContract(e->contract);
  }
  s.time = world_.time;
  s.step = world_.step;
  s.dt = world_.dt;
  s.step_rate = step_rate_;
  s.real_time_factor = measured_rtf_;
  s.target_real_time_factor = real_time_factor_;
  s.num_bodies = static_cast<int32_t>(world_.bodies().size());
  s.num_sleeping = static_cast<int32_t>(world_.SleepingCount());
  s.num_contacts = static_cast<int32_t>(contacts_.size());
  s.max_penetration = last_stats_.max_penetration;
  s.solver_iterations = last_stats_.iterations;
  s.commands_accepted = accepted_;
  s.commands_rejected = rejected_;
  s.commands_unauthenticated = unauthenticated_;
  s.commands_limited = limited_;
  s.num_controllers = static_cast<int32_t>(lockstep_.size());
  s.controllers = lockstep_.Describe();
  s.late_events = lockstep_.late_events();
  s.last_late_event = lockstep_.last_late_event();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.last_error = last_error_;
  }
  PublishMessage(transport_, Channel("STATUS"), s);
}

void SimServer::PrintLiveLine(bool final_line) {
  if (!options_.live_line) return;
  static const bool tty = isatty(fileno(stderr));
  const auto now = Clock::now();
  const auto period = tty ? std::chrono::milliseconds(250) : std::chrono::milliseconds(5000);
  if (!final_line && now - last_live_line_ < period) return;
  last_live_line_ = now;
  std::fprintf(stderr, "%sstep %8lld  t %9.3f s  rtf %5.2f  bodies %5zu  contacts %5zu  %-8s %s%s",
               tty ? "\r\033[K" : "", static_cast<long long>(world_.step), world_.time, measured_rtf_,
               world_.bodies().size(), contacts_.size(), method_->Name(), paused_ && step_budget_ == 0 ? "paused" : "running",
               tty && !final_line ? "" : "\n");
  std::fflush(stderr);
}

bool SimServer::Tick() {
  const bool changed = DrainInbox();
  if (paused_ && step_budget_ == 0) {
    if (changed) PublishState();
    return false;
  }
  if (mode_ == RunMode::kLockstep && !LockstepReady(nullptr)) return false;
  StepWorld();
  return true;
}

void SimServer::Run(const std::atomic<bool>& stop) {
  const auto status_period = std::chrono::duration<double>(1.0 / std::max(1e-3, options_.status_rate_hz));
  auto next_status = Clock::now() + std::chrono::duration_cast<Clock::duration>(status_period);
  Clock::time_point wall_anchor = Clock::now();
  double sim_anchor = world_.time;
  while (!stop.load()) {
    const auto now = Clock::now();
    if (now >= next_status) {
      PublishStatus(now);
      next_status = now + std::chrono::duration_cast<Clock::duration>(status_period);
    }
    PrintLiveLine(false);
    const bool changed = DrainInbox();
    const bool stepping = step_budget_ > 0;
    if (paused_ && !stepping) {
      if (changed) PublishState();
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait_for(lock, std::chrono::milliseconds(50), [this, &stop] { return !inbox_.empty() || stop.load(); });
      reanchor_ = true;
      continue;
    }
    if (mode_ == RunMode::kRealtime && !stepping) {
      if (reanchor_) {
        wall_anchor = Clock::now();
        sim_anchor = world_.time;
        reanchor_ = false;
      }
      // pace: step k is due when the wall clock reaches anchor + sim time / rtf
      const auto due = wall_anchor + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>((world_.time - sim_anchor) / real_time_factor_));
      const auto t = Clock::now();
      if (t < due) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait_until(lock, std::min(due, next_status), [this, &stop] { return !inbox_.empty() || stop.load(); });
        continue;
      }
      // far behind (a slow step or a long pause): do not try to catch up in a burst
      if (t - due > std::chrono::milliseconds(250)) reanchor_ = true;
    } else {
      reanchor_ = true;
    }
    if (mode_ == RunMode::kLockstep && !LockstepReady(&stop)) continue;
    StepWorld();
  }
  CancelStepCommands("server stopping");
  PublishStatus(Clock::now());
  PrintLiveLine(true);
}

}  // namespace contactsim
