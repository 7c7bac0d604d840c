#include "service/server/lockstep_gate.h"

#include <contactsim/input_t.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>

namespace contactsim {
namespace {

constexpr std::chrono::milliseconds kStateResendPeriod{200};

}  // namespace

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
  m.joints = EncodeActuatorUpdate(in.joints);
  std::string bytes(m.getEncodedSize(), '\0');
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

LockstepGate::LockstepGate(const ServerOptions& options)
    : late_policy_(options.late_policy), late_timeout_(options.late_timeout) {}

Outcome LockstepGate::Apply(Command& cmd, int64_t step) {
  using K = Command::Kind;
  Status st;
  switch (cmd.kind) {
    case K::kRegisterController: {
      const LatePolicy policy = cmd.late_default ? late_policy_ : cmd.late_policy;
      const double timeout = cmd.late_timeout > 0.0 ? cmd.late_timeout : late_timeout_;
      if (!(st = lockstep_.Register(cmd.client_id, policy, timeout)).ok()) return Outcome::Failed(st);
      republish_state_ = true;  // its first input needs the current STATE
      spdlog::info("controller \"{}\" registered (late policy {}, timeout {} s)", cmd.client_id,
                   LatePolicyName(policy), timeout);
      return Outcome::Done("controller \"" + cmd.client_id + "\" registered; send input for step " +
                               std::to_string(step + 1),
                           false);
    }
    case K::kReleaseController:
      if (!(st = lockstep_.Release(cmd.client_id)).ok()) return Outcome::Failed(st);
      spdlog::info("controller \"{}\" released", cmd.client_id);
      return Outcome::Done("controller \"" + cmd.client_id + "\" released", false);
    case K::kInput: {
      // a good input is acknowledged by the STATE of its step, not a reply
      if (!(st = lockstep_.Offer(std::move(cmd.input), step + 1)).ok()) return Outcome::Failed(st);
      Outcome o;
      o.deferred = true;
      return o;
    }
    default:
      return Outcome::Failed(Status::Internal("not a lockstep command"));
  }
}

bool LockstepGate::Ready(int64_t k, bool state_sent, const std::function<void()>& publish_state,
                         Clock::time_point* until) {
  if (!lockstep_.active() || lockstep_.Ready(k)) {
    waiting_ = false;
    return true;
  }
  const auto now = Clock::now();
  // STATE k-1 goes out again every kStateResendPeriod while the server
  // waits: a STATE or an input lost on UDP, or an input that raced ahead of
  // its controller's registration, would otherwise stall a `wait` policy
  // forever. Controllers answer a repeated STATE by resending their input.
  const bool resend = waiting_ && now - last_state_ >= kStateResendPeriod;
  if (republish_state_ || !state_sent || resend) {
    republish_state_ = false;
    publish_state();
    last_state_ = now;
  }
  if (until == nullptr) return false;  // Tick: tests drive the inputs
  if (!waiting_) {
    waiting_ = true;
    wait_start_ = now;
    last_state_ = now;
  }
  const double waited = std::chrono::duration<double>(now - wait_start_).count();
  for (const std::string& line : lockstep_.ResolveLate(k, waited)) spdlog::warn("{}", line);
  if (lockstep_.Ready(k)) {
    waiting_ = false;
    return true;
  }
  // wake for an input, the next late deadline, or (at the latest) 50 ms for
  // STATUS, the STATE resend and stop
  *until = now + std::chrono::milliseconds(50);
  const double deadline = lockstep_.NextDeadline(k);
  if (deadline >= 0.0) {
    *until = std::min(*until, wait_start_ + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(deadline)));
  }
  return false;
}

std::vector<ControllerInput> LockstepGate::Take(int64_t step) {
  std::vector<ControllerInput> inputs = lockstep_.Take(step);
  input_digest_ = DigestInputs(inputs);
  return inputs;
}

void LockstepGate::DescribeInto(status_t* s) const {
  s->num_controllers = static_cast<int32_t>(lockstep_.size());
  s->controllers = lockstep_.Describe();
  s->late_events = lockstep_.late_events();
  s->last_late_event = lockstep_.last_late_event();
}

}  // namespace contactsim
