#include "service/server/sim_server.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "service/contact/contact_method_registry.h"
#include "service/contact/method_support.h"

namespace contactsim {

SimServer::SimServer(ServerOptions options, Transport* transport)
    : options_(std::move(options)),
      paused_(options_.start_paused),
      mode_(options_.mode),
      real_time_factor_(options_.real_time_factor),
      status_period_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(1.0 / std::max(1e-3, options_.status_rate_hz)))),
      publisher_(options_, transport),
      steps_(&publisher_),
      batch_(options_, &publisher_, &world_, &method_,
             {[this](Command& cmd) { return Apply(cmd); },
              [this](World&& world, std::shared_ptr<ContactMethod>&& method) {
                // an undo within one step boundary: no detection ran since
                // the copy, so the kept manifolds are still the world's
                ReplaceWorld(std::move(world), std::move(method), detector_.manifolds().entries());
                contacts_.clear();
                publisher_.UpdateRates(world_.dt);
              }}),
      lockstep_(options_),
      intake_(options_, &batch_) {
  if (options_.arm_driver) arm_ = std::make_unique<ArmDriver>(*options_.arm_driver);
  if (options_.wsg_driver) wsg_ = std::make_unique<WsgDriver>(*options_.wsg_driver);
}

Status SimServer::Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method) {
  Status st = detector_.SetBroadphase(options_.broadphase);
  if (!st.ok()) return st;
  if (!(st = detector_.SetThreads(options_.threads)).ok()) return st;
  detector_.SetManifoldReuse(options_.manifold_reuse);
  if (scene != nullptr) {
    if (!(st = BuildWorld(*scene, &world_)).ok()) return st;
  }
  if (!(st = StartArmDriver()).ok()) return st;
  if (!(st = StartWsgDriver()).ok()) return st;
  world_.sleep.enabled = options_.sleep;  // a recovered snapshot brings its own
  // a configured method that cannot honour the configured scene (method_support.h)
  if (!(st = CheckMethodSupports(method->Name(), world_)).ok()) return st;
  method_ = std::move(method);
  if (!(st = Recover()).ok()) return st;
  publisher_.UpdateRates(world_.dt);
  PublishStatus(Clock::now());
  PublishState();
  PublishArmStatus();
  PublishWsgStatus();
  PublishModelInfo();
  return Status::Ok();
}

Outcome SimServer::Apply(Command& cmd) {
  using K = Command::Kind;
  switch (cmd.kind) {
    case K::kAddBody: case K::kRemoveBody: case K::kSetPose: case K::kSetVelocity: case K::kApplyForce:
    case K::kApplyImpulse: case K::kSetMass: case K::kSetMaterial: case K::kSetFilter: case K::kAddJoint:
    case K::kRemoveJoint:
      return ApplyBodyCommand(cmd);
    case K::kSnapshot: case K::kRestore: case K::kRewind:
      return ApplySnapshotCommand(cmd);
    case K::kLoadModel: case K::kRemoveModel: case K::kModelInfo:
      return ApplyModelCommand(cmd);
    case K::kSetActuators: case K::kClearActuators: case K::kJointStateQuery:
      return ApplyActuatorCommand(cmd);
    case K::kInput: {
      const Status st = CheckInputJoints(&cmd.input);
      if (!st.ok()) return Outcome::Failed(st);
      return lockstep_.Apply(cmd, world_.step);
    }
    case K::kRegisterController: case K::kReleaseController:
      return lockstep_.Apply(cmd, world_.step);
    case K::kAddRangeSensor: case K::kAddContactSensor: case K::kRemoveSensor:
      return ApplySensorCommand(cmd);
    case K::kRayCast:
      return ApplyRayCast(cmd);
    case K::kArmCommand:
      return ApplyArmCommand(cmd);
    case K::kWsgCommand:
      return ApplyWsgCommand(cmd);
    default:
      return ApplyWorldCommand(cmd);
  }
}

void SimServer::ReplaceWorld(World&& world, std::shared_ptr<ContactMethod> method,
                             std::vector<CachedManifold> manifolds) {
  world_ = std::move(world);
  method_ = std::move(method);
  detector_.Reset();
  detector_.RestoreManifolds(std::move(manifolds));
  sleep_.Reset();
  standing_actuators_.clear();
}

void SimServer::StartOver() {
  contacts_.clear();
  publisher_.UpdateRates(world_.dt);
  StartTimeline();
  ClearFault();
}

// ---- the loop ---------------------------------------------------------------

void SimServer::SimulateStep() {
  if (arm_) arm_->BeforeStep(&world_);
  // the server reads the contact report after any step: the CONTACTS
  // channel when due, the sensors between steps, the status's count, and
  // the contacts island sleep keeps while their bodies sleep
  method_->RequestContactReport(true);
  last_stats_ = sleep_.Step(world_, *method_, detector_, &contacts_);
  RestoreStandingActuators();
  steps_.ReportRewindProgress(world_.step);
}

void SimServer::StepWorld() {
  ApplyInputs();
  runaway_.BeforeStep(world_);
  SimulateStep();
  const Status sound = runaway_.AfterStep(world_);
  if (!sound.ok()) return OnBlowUp(sound);
  steps_.Took();
  if (options_.snapshot_every > 0 && world_.step % options_.snapshot_every == 0) TakePeriodicSnapshot();
  // controllers need every STATE
  if (publisher_.StateDue(world_.step) || (mode_ == RunMode::kLockstep && lockstep_.active())) PublishState();
  if (publisher_.ContactsDue(world_.step)) publisher_.Contacts(world_, contacts_, *method_);
  PublishArmStatus();
  PublishWsgStatus();
  FinishStepCommands();
  steps_.ReportProgress(world_.step, false);
}

void SimServer::OnBlowUp(const Status& why) {
  fault_ = why.message();
  spdlog::error("{} under {}; stepping stops until RESET, a scene or snapshot load, or REWIND", fault_,
                method_->Name());
  paused_ = true;
  CancelStepCommands(fault_);
  PublishStatus(Clock::now());  // at once: a client need not wait for the next heartbeat
}

void SimServer::ClearFault() {
  fault_.clear();
  runaway_.Rebase(world_);
}

// Stepping a world that blew up would only publish more of its garbage.
Status SimServer::RefusedByFault() const {
  return Status::FailedPrecondition(fault_ + "; RESET, load a scene or a snapshot, or REWIND to an earlier step first");
}

void SimServer::ApplyInputs() {
  for (const ControllerInput& in : lockstep_.Take(world_.step + 1)) {
    const Status st = batch_.Record(RecordKind::kInput, EncodeInput(in));
    if (!st.ok()) spdlog::error("input of \"{}\" for step {}: {}", in.controller, in.step, st.message());
    ApplyInput(in, true);
  }
}

// Each force and torque acts for this one step (a zero-duration wrench).
// An unknown or non-dynamic body is skipped; a live input's sender hears
// of it by an error reply (a replay skips it the same way, silently).
void SimServer::ApplyInput(const ControllerInput& in, bool live) {
  for (const BodyInput& b : in.bodies) {
    const RigidBody* body = world_.Find(b.body);
    if (body == nullptr || !body->IsDynamic()) {
      if (live) {
        const char* why = body == nullptr ? " is unknown" : " is not dynamic";
        batch_.SendReply(in.controller, in.request_id,
                         Status::NotFound("input for step " + std::to_string(in.step) + ": body " +
                                          std::to_string(b.body) + why),
                         "");
      }
      continue;
    }
    world_.AddWrench({b.body, b.force, b.torque, 0.0});
  }
  ApplyInputJoints(in, live);
}

bool SimServer::LockstepReady(Clock::time_point* until) {
  return lockstep_.Ready(world_.step + 1, publisher_.StateSentAt(world_.step), [this] { PublishState(); }, until);
}

// Replies to the STEP commands whose last step is done, after their STATE.
void SimServer::FinishStepCommands() {
  for (const StepRequests::Request& r : steps_.Done(world_.step)) {
    if (!publisher_.StateSentAt(world_.step)) PublishState();
    // recovery brings the world back to the last step a reply acknowledged
    Status st = batch_.Record(RecordKind::kStepTo, "");
    if (st.ok()) st = batch_.journal().Sync();
    if (!st.ok()) st = Status::Internal("steps taken, but a restart would not keep them: " + st.message());
    batch_.SendReply(r.client_id, r.request_id, st, "at step " + std::to_string(world_.step));
  }
}

void SimServer::CancelStepCommands(const std::string& why) {
  for (const StepRequests::Answer& a : steps_.Cancel(why, world_.step)) {
    batch_.SendReply(a.client_id, a.request_id, a.status, "");
  }
}

void SimServer::PublishState() {
  PublishJointState();  // first: a client holding STATE k holds JOINT_STATE k
  publisher_.State(world_, lockstep_.input_digest());
  PublishSensors();
}

void SimServer::PublishStatus(Clock::time_point now) {
  status_t s;
  s.version = CONTACTSIM_VERSION;
  s.mode = static_cast<int8_t>(mode_);  // equal values by design
  s.paused = Halted();
  s.method = method_->Name();
  for (const auto& [k, v] : method_->Params()) s.method_params += (s.method_params.empty() ? "" : " ") + k + "=" + v;
  if (const ContactMethodEntry* e = FindContactMethod(method_->Name())) {
    s.method_contract = DescribeContract(e->contract);
  }
  s.time = world_.time;
  s.step = world_.step;
  s.dt = world_.dt;
  s.target_real_time_factor = real_time_factor_;
  s.num_bodies = static_cast<int32_t>(world_.bodies().size());
  s.num_sleeping = static_cast<int32_t>(world_.SleepingCount());
  s.num_contacts = static_cast<int32_t>(contacts_.size());
  s.max_penetration = last_stats_.max_penetration;
  s.solver_iterations = last_stats_.iterations;
  batch_.CountInto(&s);
  lockstep_.DescribeInto(&s);
  s.fault = fault_;
  publisher_.Status(std::move(s), now);
}

bool SimServer::Tick() {
  const bool changed = batch_.Drain();
  if (changed) runaway_.Rebase(world_);
  PublishModelInfo();
  if (Halted()) {
    if (changed) PublishState();
    return false;
  }
  if (mode_ == RunMode::kLockstep && !LockstepReady(nullptr)) return false;
  StepWorld();
  return true;
}

SimServer::Pause SimServer::Turn(Clock::time_point* until, bool lockstep_only) {
  const auto now = Clock::now();
  if (now >= next_status_) {
    PublishStatus(now);
    next_status_ = now + status_period_;
  }
  publisher_.LiveLine(false, world_, contacts_.size(), method_->Name(), Halted());
  const bool changed = batch_.Drain();
  if (changed) runaway_.Rebase(world_);
  PublishModelInfo();
  const bool stepping = steps_.owed();
  if (paused_ && !stepping) {
    if (changed) PublishState();
    *until = Clock::now() + std::chrono::milliseconds(50);
    reanchor_ = true;
    return Pause::kForCommands;
  }
  // the input's thread steps only on inputs: without a controller a
  // lockstep world runs free, which is the simulation thread's loop
  if (lockstep_only && (mode_ != RunMode::kLockstep || !lockstep_.active())) {
    *until = Clock::now();
    return Pause::kForCommands;
  }
  if (mode_ == RunMode::kRealtime && !stepping) {
    if (reanchor_) {
      wall_anchor_ = Clock::now();
      sim_anchor_ = world_.time;
      reanchor_ = false;
    }
    // pace: step k is due when the wall clock reaches anchor + sim time / rtf
    const auto due = wall_anchor_ + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>((world_.time - sim_anchor_) / real_time_factor_));
    const auto t = Clock::now();
    if (t < due) {
      *until = std::min(due, next_status_);
      return Pause::kForCommands;
    }
    // far behind (a slow step or a long pause): do not try to catch up in a burst
    if (t - due > std::chrono::milliseconds(250)) reanchor_ = true;
  } else {
    reanchor_ = true;
  }
  if (mode_ == RunMode::kLockstep && !LockstepReady(until)) {
    *until = std::min(*until, next_status_);
    return Pause::kForInputs;
  }
  StepWorld();
  return Pause::kNone;
}

void SimServer::OnMessage(const std::string& channel, const void* data, int size) {
  if (parked_.load()) {
    std::unique_lock<std::mutex> turn(turn_mutex_, std::try_to_lock);
    // with the turn held, parked_ is exact: the simulation thread sets it
    // before it lets go of the turn and clears it once it has it back
    if (turn.owns_lock() && parked_.load()) {
      batch_.HoldWakeUps(true);  // this thread drains what it queues
      intake_.OnMessage(channel, data, size);
      batch_.HoldWakeUps(false);
      TurnOnInput();
      return;
    }
  }
  intake_.OnMessage(channel, data, size);
}

void SimServer::TurnOnInput() {
  Clock::time_point until;
  Pause pause;
  while ((pause = Turn(&until, true)) == Pause::kNone) {
  }
  // The simulation thread sleeps until parked_until_ unless woken. A later
  // wait for inputs needs no wake-up (it wakes early, finds the inputs
  // missing and waits again); anything else, or an earlier deadline (a
  // controller registered with a shorter timeout), does.
  if (pause != Pause::kForInputs || until < parked_until_) batch_.Wake();
}

void SimServer::Run(const std::atomic<bool>& stop) {
  std::unique_lock<std::mutex> turn(turn_mutex_);
  next_status_ = Clock::now() + status_period_;
  while (!stop.load()) {
    Clock::time_point until;
    const Pause pause = Turn(&until, false);
    if (pause == Pause::kNone) continue;
    if (pause == Pause::kForInputs && options_.lockstep_step_on_input) {
      parked_until_ = until;
      parked_.store(true);
      turn.unlock();
      batch_.Wait(until, stop);
      turn.lock();
      parked_.store(false);
    } else {
      batch_.Wait(until, stop);
    }
  }
  CancelStepCommands("server stopping");
  PublishStatus(Clock::now());
  publisher_.LiveLine(true, world_, contacts_.size(), method_->Name(), Halted());
}

}  // namespace contactsim
