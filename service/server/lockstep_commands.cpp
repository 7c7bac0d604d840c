// SimServer's lockstep handling (docs/lockstep.md): controller registration,
// inputs, and the wait before each step. Simulation thread, except
// OnInputMessage (LCM thread).
#include <contactsim/input_t.hpp>
#include <contactsim/reply_t.hpp>
#include <spdlog/spdlog.h>

#include "service/server/sim_server.h"

namespace contactsim {
namespace {

constexpr std::chrono::milliseconds kStateResendPeriod{200};

// The input as applied, for the journal (a reused input carries its new step).
std::string EncodeInput(const ControllerInput& in) {
  input_t m;
  m.client_id = in.controller;
  m.request_id = in.request_id;
  m.step = in.step;
  m.num_bodies = static_cast<int32_t>(in.bodies.size());
  for (const BodyInput& b : in.bodies) {
    m.body_ids.push_back(b.body);
    m.forces.push_back({b.force.x(), b.force.y(), b.force.z()});
    m.torques.push_back({b.torque.x(), b.torque.y(), b.torque.z()});
  }
  std::string bytes(m.getEncodedSize(), '\0');
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace

Outcome SimServer::ApplyLockstepCommand(Command& cmd) {
  using K = Command::Kind;
  Status st;
  switch (cmd.kind) {
    case K::kRegisterController: {
      const LatePolicy policy = cmd.late_default ? options_.late_policy : cmd.late_policy;
      const double timeout = cmd.late_timeout > 0.0 ? cmd.late_timeout : options_.late_timeout;
      st = lockstep_.Register(cmd.client_id, policy, timeout);
      if (st.ok()) {
        republish_state_ = true;  // its first input needs the current STATE
        spdlog::info("controller \"{}\" registered (late policy {}, timeout {} s)", cmd.client_id,
                     LatePolicyName(policy), timeout);
      }
      if (!st.ok()) return Outcome::Failed(st);
      return Outcome::Done("controller \"" + cmd.client_id + "\" registered; send input for step " +
                               std::to_string(world_.step + 1),
                           false);
    }
    case K::kReleaseController:
      st = lockstep_.Release(cmd.client_id);
      if (st.ok()) spdlog::info("controller \"{}\" released", cmd.client_id);
      if (!st.ok()) return Outcome::Failed(st);
      return Outcome::Done("controller \"" + cmd.client_id + "\" released", false);
    case K::kInput: {
      // a good input is acknowledged by the STATE of its step, not a reply
      st = lockstep_.Offer(std::move(cmd.input), world_.step + 1);
      if (!st.ok()) return Outcome::Failed(st);
      Outcome o;
      o.deferred = true;
      return o;
    }
    default:
      return Outcome::Failed(Status::Internal("not a lockstep command"));
  }
}

// Before step k = world.step + 1: true when every controller's input for k
// is here (or its late policy decided). Otherwise publishes STATE k-1 if a
// controller has not seen it, waits a little for inputs (with `stop`) and
// returns false so that the loop drains the inbox and asks again.
bool SimServer::LockstepReady(const std::atomic<bool>* stop) {
  const int64_t k = world_.step + 1;
  if (!lockstep_.active() || lockstep_.Ready(k)) {
    lockstep_waiting_ = false;
    return true;
  }
  const auto now = std::chrono::steady_clock::now();
  // STATE k-1 goes out again every kStateResendPeriod while the server
  // waits: a STATE or an input lost on UDP, or an input that raced ahead of
  // its controller's registration, would otherwise stall a `wait` policy
  // forever. Controllers answer a repeated STATE by resending their input.
  const bool resend = lockstep_waiting_ && now - lockstep_last_state_ >= kStateResendPeriod;
  if (republish_state_ || last_state_step_ != world_.step || resend) {
    republish_state_ = false;
    PublishState();
    lockstep_last_state_ = now;
  }
  if (stop == nullptr) return false;  // Tick: tests drive the inputs
  if (!lockstep_waiting_) {
    lockstep_waiting_ = true;
    lockstep_wait_start_ = now;
    lockstep_last_state_ = now;
  }
  const double waited = std::chrono::duration<double>(now - lockstep_wait_start_).count();
  for (const std::string& line : lockstep_.ResolveLate(k, waited)) spdlog::warn("{}", line);
  if (lockstep_.Ready(k)) {
    lockstep_waiting_ = false;
    return true;
  }
  // wake for an input, the next late deadline, or (at the latest) 50 ms for
  // STATUS, the STATE resend and stop
  auto until = now + std::chrono::milliseconds(50);
  const double deadline = lockstep_.NextDeadline(k);
  if (deadline >= 0.0) {
    until = std::min(until, lockstep_wait_start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                       std::chrono::duration<double>(deadline)));
  }
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_until(lock, until, [this, stop] { return !inbox_.empty() || stop->load(); });
  return false;
}

void SimServer::ApplyInputs() {
  const std::vector<ControllerInput> inputs = lockstep_.Take(world_.step + 1);
  input_digest_ = DigestInputs(inputs);
  for (const ControllerInput& in : inputs) {
    const Status st = JournalCommand(RecordKind::kInput, EncodeInput(in));
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
        SendReply(in.controller, in.request_id,
                  Status::NotFound("input for step " + std::to_string(in.step) + ": body " + std::to_string(b.body) +
                                   (body == nullptr ? " is unknown" : " is not dynamic")),
                  "");
      }
      continue;
    }
    world_.AddWrench({b.body, b.force, b.torque, 0.0});
  }
}

}  // namespace contactsim
