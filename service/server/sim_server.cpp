#include "service/server/sim_server.h"

#include <contactsim/status_t.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <thread>
#include <unistd.h>

#include "service/server/command_decoder.h"
#include "service/server/messages.h"

namespace contactsim {

using Clock = std::chrono::steady_clock;

SimServer::SimServer(ServerOptions options, Transport* transport)
    : options_(std::move(options)), transport_(transport), snapshots_(options_.max_snapshots) {
  paused_ = options_.start_paused;
  mode_ = options_.mode;
  real_time_factor_ = options_.real_time_factor;
}

Status SimServer::Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method) {
  Status st = detector_.SetBroadphase(options_.broadphase);
  if (!st.ok()) return st;
  if (scene != nullptr) {
    if (!(st = BuildWorld(*scene, &world_)).ok()) return st;
  }
  method_ = std::move(method);
  if (!(st = Recover()).ok()) return st;
  UpdateRates();
  last_status_wall_ = Clock::now();
  PublishStatus(last_status_wall_);
  PublishState();
  return Status::Ok();
}

// ---- LCM thread -----------------------------------------------------------

void SimServer::Reject(const std::string& client_id, int64_t request_id, int32_t code, const std::string& message,
                       const char* channel) {
  ++rejected_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    last_error_ = message;
  }
  spdlog::warn("rejected {} from \"{}\" #{}: {}", channel, client_id, request_id, message);
  reply_t r;
  r.client_id = client_id;
  r.request_id = request_id;
  r.code = code;
  r.message = message;
  // the world belongs to the simulation thread: early errors carry no step
  r.step = -1;
  r.time = 0.0;
  r.num_ids = 0;
  const int n = r.getEncodedSize();
  std::vector<uint8_t> buf(n);
  r.encode(buf.data(), 0, n);
  transport_->Publish(Channel("REPLY"), buf.data(), n);
}

// Decodes one command payload of type Msg from `suffix`'s channel and checks
// it with decode(msg, &cmd): a bad one is answered at once, a good one queued.
template <typename Msg, typename Decode>
void SimServer::Receive(const void* data, int size, const char* suffix, Decode decode) {
  Msg msg;
  if (size > kMaxCommandBytes || msg.decode(data, 0, size) < 0) {
    Reject("", -1, reply_t::DECODE_ERROR,
           std::string("undecodable ") + Msg::getTypeName() + " payload of " + std::to_string(size) + " bytes on " +
               Channel(suffix),
           suffix);
    return;
  }
  Command cmd;
  const Status st = decode(msg, &cmd);
  if (!st.ok()) return Reject(msg.client_id, msg.request_id, static_cast<int32_t>(st.code()), st.message(), suffix);
  cmd.payload.assign(static_cast<const char*>(data), size);
  Enqueue(std::move(cmd));
}

void SimServer::OnBodyMessage(const void* data, int size) {
  Receive<body_cmd_t>(data, size, "BODY_CMD", [this](const body_cmd_t& m, Command* cmd) {
    return DecodeBodyCommand(m, default_material_, cmd);
  });
}

void SimServer::OnSceneMessage(const void* data, int size) {
  Receive<scene_cmd_t>(data, size, "SCENE_CMD", DecodeSceneCommand);
}

void SimServer::OnJointMessage(const void* data, int size) {
  Receive<joint_cmd_t>(data, size, "JOINT_CMD", DecodeJointCommand);
}

void SimServer::Enqueue(Command cmd) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    inbox_.push_back(std::move(cmd));
  }
  wake_.notify_one();
}

// ---- simulation thread ----------------------------------------------------

void SimServer::SendReply(const std::string& client_id, int64_t request_id, const Status& status,
                          const std::string& message, const std::vector<int64_t>& ids) {
  last_reply_ok_ = status.ok();
  if (replaying_) return;
  reply_t r = MakeReply(client_id, request_id, status, world_);
  if (status.ok()) {
    r.message = message;
    ++accepted_;
  } else {
    ++rejected_;
    std::lock_guard<std::mutex> lock(mutex_);
    last_error_ = status.message();
  }
  if (!status.ok()) spdlog::warn("rejected command from \"{}\" #{}: {}", client_id, request_id, status.message());
  r.ids = ids;
  r.num_ids = static_cast<int32_t>(ids.size());
  const int n = r.getEncodedSize();
  std::vector<uint8_t> buf(n);
  r.encode(buf.data(), 0, n);
  if (hold_replies_) {
    held_replies_.push_back(std::move(buf));
  } else {
    PublishReply(buf);
  }
}

// Commands whose effect the journal must carry to a replay: the ones that
// change the world without replacing it (reset, load and restore start a
// new timeline from a snapshot instead).
static bool Journaled(Command::Kind kind) {
  using K = Command::Kind;
  switch (kind) {
    case K::kAddBody: case K::kRemoveBody: case K::kSetPose: case K::kSetVelocity: case K::kApplyForce:
    case K::kApplyImpulse: case K::kSetMass: case K::kSetMaterial: case K::kSetGravity: case K::kSetTimestep:
    case K::kSetMethod: case K::kAddJoint: case K::kRemoveJoint:
      return true;
    default:
      return false;
  }
}

static RecordKind RecordKindOf(Command::Kind kind) {
  if (kind <= Command::Kind::kSetMaterial) return RecordKind::kBodyCommand;
  if (kind == Command::Kind::kAddJoint || kind == Command::Kind::kRemoveJoint) return RecordKind::kJointCommand;
  return RecordKind::kSceneCommand;
}

bool SimServer::DrainInbox() {
  std::deque<Command> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    batch.swap(inbox_);
  }
  bool changed = false;
  // group commit: the batch's records are synced once, before its replies
  hold_replies_ = true;
  for (Command& cmd : batch) {
    last_reply_ok_ = false;
    changed |= Apply(cmd);
    if (last_reply_ok_ && Journaled(cmd.kind)) {
      JournalCommand(RecordKindOf(cmd.kind), cmd.payload);
    }
  }
  hold_replies_ = false;
  FlushReplies();
  return changed;
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
    SendReply(p.client_id, p.request_id, Status::FailedPrecondition("step interrupted: " + why), "");
  }
  pending_steps_.clear();
  step_budget_ = 0;
}

// Applies one command; returns true if the world's content changed.
bool SimServer::Apply(Command& cmd) {
  using K = Command::Kind;
  const std::string& cid = cmd.client_id;
  const int64_t rid = cmd.request_id;
  auto body_or_reply = [&](bool need_dynamic) -> RigidBody* {
    RigidBody* b = world_.Find(cmd.body_id);
    if (b == nullptr) {
      SendReply(cid, rid, Status::NotFound("unknown body id " + std::to_string(cmd.body_id)), "");
    } else if (need_dynamic && !b->IsDynamic()) {
      const char* what = b->motion == MotionType::kKinematic ? " is kinematic (infinite mass)" : " is static";
      SendReply(cid, rid, Status::FailedPrecondition("body " + std::to_string(cmd.body_id) + what), "");
      return nullptr;
    }
    return b;
  };
  switch (cmd.kind) {
    case K::kAddBody: {
      if (static_cast<int>(world_.bodies().size()) >= options_.max_bodies) {
        SendReply(cid, rid, Status::FailedPrecondition("the world holds max_bodies = " +
                                                       std::to_string(options_.max_bodies) + " bodies already"), "");
        return false;
      }
      const char* shape = ShapeTypeName(cmd.new_body.shape.type);
      const BodyId id = world_.AddBody(std::move(cmd.new_body));
      detector_.Reset();
      SendReply(cid, rid, Status::Ok(), std::string("added ") + shape + " " + std::to_string(id), {id});
      return true;
    }
    case K::kRemoveBody: {
      const size_t joints = world_.joints().size();
      Status st = world_.RemoveBody(cmd.body_id);
      if (st.ok()) detector_.Reset();
      std::string text = "removed body " + std::to_string(cmd.body_id);
      if (world_.joints().size() < joints) text += " and its " + std::to_string(joints - world_.joints().size()) + " joint(s)";
      SendReply(cid, rid, st, text);
      return st.ok();
    }
    case K::kAddJoint: {
      JointId id = 0;
      const Status st = world_.AddJoint(cmd.joint, &id);
      SendReply(cid, rid, st, std::string("added ") + JointKindName(cmd.joint.kind) + " joint " + std::to_string(id),
                st.ok() ? std::vector<int64_t>{id} : std::vector<int64_t>{});
      return st.ok();
    }
    case K::kRemoveJoint: {
      const Status st = world_.RemoveJoint(cmd.joint_id);
      SendReply(cid, rid, st, "removed joint " + std::to_string(cmd.joint_id));
      return st.ok();
    }
    case K::kSetPose: {
      RigidBody* b = body_or_reply(false);
      if (b == nullptr) return false;
      const Vec3 v = b->LinearVelocity(), w = b->AngularVelocity();
      b->x = cmd.position;
      b->q = cmd.orientation;
      b->SetVelocity(v, w);  // keep w, not L, across the rotation
      SendReply(cid, rid, Status::Ok(), "pose of body " + std::to_string(cmd.body_id) + " set");
      return true;
    }
    case K::kSetVelocity: {
      RigidBody* b = body_or_reply(false);
      if (b == nullptr) return false;
      if (b->motion == MotionType::kStatic) {
        SendReply(cid, rid, Status::FailedPrecondition("body " + std::to_string(cmd.body_id) + " is static"), "");
        return false;
      }
      b->SetVelocity(cmd.linear, cmd.angular);
      SendReply(cid, rid, Status::Ok(), "velocity of body " + std::to_string(cmd.body_id) + " set");
      return true;
    }
    case K::kApplyForce: {
      RigidBody* b = body_or_reply(true);
      if (b == nullptr) return false;
      world_.AddWrench({cmd.body_id, cmd.linear, cmd.angular, cmd.duration});
      SendReply(cid, rid, Status::Ok(), "force on body " + std::to_string(cmd.body_id) + " for " +
                                            std::to_string(cmd.duration) + " s");
      return true;
    }
    case K::kApplyImpulse: {
      RigidBody* b = body_or_reply(true);
      if (b == nullptr) return false;
      b->ApplyImpulse(cmd.linear, cmd.point.value_or(b->x));
      SendReply(cid, rid, Status::Ok(), "impulse on body " + std::to_string(cmd.body_id));
      return true;
    }
    case K::kSetMass: {
      RigidBody* b = body_or_reply(true);
      if (b == nullptr) return false;
      if (cmd.mass) b->SetMass(*cmd.mass);
      else b->SetMassFromDensity(*cmd.density);
      SendReply(cid, rid, Status::Ok(), "mass of body " + std::to_string(cmd.body_id) + " is " +
                                            std::to_string(b->mass) + " kg");
      return true;
    }
    case K::kSetMaterial: {
      RigidBody* b = body_or_reply(false);
      if (b == nullptr) return false;
      if (cmd.restitution) b->material.restitution = *cmd.restitution;
      if (cmd.friction) b->material.friction = *cmd.friction;
      SendReply(cid, rid, Status::Ok(), "material of body " + std::to_string(cmd.body_id) + " set");
      return true;
    }
    case K::kReset:
      CancelStepCommands("reset");
      world_.Clear();
      detector_.Reset();
      method_->ResetCaches();
      contacts_.clear();
      UpdateRates();
      StartTimeline();
      SendReply(cid, rid, Status::Ok(), "world reset");
      return true;
    case K::kLoadScene: {
      CancelStepCommands("scene loaded");
      Status st = BuildWorld(*cmd.scene, &world_);
      if (!st.ok()) {
        SendReply(cid, rid, st, "");
        return false;
      }
      detector_.Reset();
      if (cmd.method) method_ = cmd.method;
      method_->ResetCaches();
      contacts_.clear();
      UpdateRates();
      StartTimeline();
      SendReply(cid, rid, Status::Ok(), "loaded " + cmd.scene_path + " (" + std::to_string(world_.bodies().size()) +
                                            " bodies)");
      return true;
    }
    case K::kSetGravity:
      world_.gravity = cmd.gravity;
      SendReply(cid, rid, Status::Ok(), "gravity set");
      return true;
    case K::kSetTimestep:
      world_.dt = cmd.dt;
      UpdateRates();
      SendReply(cid, rid, Status::Ok(), "time step set");
      return true;
    case K::kSetMethod: {
      // a switch keeps every body's state and drops only the old method's caches
      method_ = cmd.method;
      std::string text = std::string("contact method ") + method_->Name();
      for (const auto& [k, v] : method_->Params()) text += " " + k + "=" + v;
      spdlog::info("{}", text);
      SendReply(cid, rid, Status::Ok(), text);
      return false;
    }
    case K::kPause:
      paused_ = true;
      SendReply(cid, rid, Status::Ok(), "paused");
      return false;
    case K::kResume:
      paused_ = false;
      reanchor_ = true;
      SendReply(cid, rid, Status::Ok(), "running");
      return false;
    case K::kStep:
      paused_ = true;
      step_budget_ += cmd.steps;
      pending_steps_.push_back({cid, rid, world_.step + step_budget_});
      return false;
    case K::kSetMode:
      mode_ = cmd.mode;
      real_time_factor_ = cmd.real_time_factor;
      reanchor_ = true;
      SendReply(cid, rid, Status::Ok(),
                mode_ == RunMode::kRealtime ? "mode realtime" : mode_ == RunMode::kFreeRun ? "mode free_run" : "mode lockstep");
      return false;
    case K::kSnapshot:
      ApplySnapshotCommand(cmd);
      return false;
    case K::kRegisterController:
    case K::kReleaseController:
    case K::kInput:
      ApplyLockstepCommand(cmd);
      return false;
    case K::kRestore:
    case K::kRewind:
      ApplySnapshotCommand(cmd);
      return last_reply_ok_;
  }
  return false;
}

void SimServer::SimulateStep() { last_stats_ = method_->Step(world_, detector_, &contacts_); }

void SimServer::StepWorld() {
  ApplyInputs();
  SimulateStep();
  if (step_budget_ > 0) --step_budget_;
  if (options_.snapshot_every > 0 && world_.step % options_.snapshot_every == 0) TakePeriodicSnapshot();
  // controllers need every STATE
  if (world_.step % state_every_ == 0 || (mode_ == RunMode::kLockstep && lockstep_.active())) PublishState();
  if (world_.step % contacts_every_ == 0) PublishContacts();
  FinishStepCommands();
}

// Replies to the STEP commands whose last step is done, after their STATE.
void SimServer::FinishStepCommands() {
  while (!pending_steps_.empty() && pending_steps_.front().target_step <= world_.step) {
    if (last_state_step_ != world_.step) PublishState();
    const PendingStep p = pending_steps_.front();
    pending_steps_.pop_front();
    // recovery brings the world back to the last step a reply acknowledged
    JournalCommand(RecordKind::kStepTo, "");
    SendReply(p.client_id, p.request_id, Status::Ok(), "at step " + std::to_string(world_.step));
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
  s.time = world_.time;
  s.step = world_.step;
  s.dt = world_.dt;
  s.step_rate = step_rate_;
  s.real_time_factor = measured_rtf_;
  s.target_real_time_factor = real_time_factor_;
  s.num_bodies = static_cast<int32_t>(world_.bodies().size());
  s.num_contacts = static_cast<int32_t>(contacts_.size());
  s.max_penetration = last_stats_.max_penetration;
  s.solver_iterations = last_stats_.iterations;
  s.commands_accepted = accepted_;
  s.commands_rejected = rejected_;
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
