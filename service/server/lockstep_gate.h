// The server's lockstep side (docs/lockstep.md): controller registration,
// inputs, and the wait before each step until every controller's input for
// it is here or its late policy has decided. Simulation thread.
#pragma once

#include <contactsim/status_t.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "service/server/command.h"
#include "service/server/command_batch.h"
#include "service/server/lockstep.h"
#include "service/server/outcome.h"
#include "service/server/server_options.h"

namespace contactsim {

class LockstepGate {
 public:
  // `batch` is waited on for inputs.
  LockstepGate(const ServerOptions& options, CommandBatch* batch);

  // REGISTER_CONTROLLER, RELEASE_CONTROLLER and INPUT with the world at `step`.
  Outcome Apply(Command& cmd, int64_t step);
  // Before step k: true when every controller's input for k is here (or its
  // late policy decided). Otherwise calls `publish_state` for STATE k-1 if a
  // controller may not have seen it (`state_sent` false, a controller just
  // registered, or again every kStateResendPeriod), waits a little for
  // inputs (null `stop`: never) and returns false so that the loop drains
  // the inbox and asks again.
  bool Ready(int64_t k, bool state_sent, const std::function<void()>& publish_state, const std::atomic<bool>* stop);
  // Removes and returns the inputs for `step`, in controller id order, and
  // keeps their digest for STATE.
  std::vector<ControllerInput> Take(int64_t step);

  bool active() const { return lockstep_.active(); }
  uint64_t input_digest() const { return input_digest_; }  // of the inputs of the last step
  void DescribeInto(status_t* s) const;

 private:
  const LatePolicy late_policy_;  // for controllers registered without one
  const double late_timeout_;
  CommandBatch* batch_;
  Lockstep lockstep_;
  uint64_t input_digest_ = 0;
  bool republish_state_ = false;  // a controller registered: it needs the current STATE
  bool waiting_ = false;
  std::chrono::steady_clock::time_point wait_start_;
  std::chrono::steady_clock::time_point last_state_;  // last STATE sent while waiting
};

// The input as applied, for the journal (a reused input carries its new step).
std::string EncodeInput(const ControllerInput& input);

}  // namespace contactsim
