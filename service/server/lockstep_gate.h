// The server's lockstep side (docs/lockstep.md): controller registration,
// inputs, and the wait before each step until every controller's input for
// it is here or its late policy has decided. The thread that holds the
// loop's turn (sim_server.h, "Threads").
#pragma once

#include <contactsim/status_t.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "service/server/command.h"
#include "service/server/lockstep.h"
#include "service/server/outcome.h"
#include "service/server/server_options.h"

namespace contactsim {

class LockstepGate {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LockstepGate(const ServerOptions& options);

  // REGISTER_CONTROLLER, RELEASE_CONTROLLER and INPUT with the world at `step`.
  Outcome Apply(Command& cmd, int64_t step);
  // Before step k: true when every controller's input for k is here (or its
  // late policy decided). Otherwise calls `publish_state` for STATE k-1 if a
  // controller may not have seen it (`state_sent` false, a controller just
  // registered, or again every kStateResendPeriod) and returns false. With
  // `until` (null in Tick: tests drive the inputs and no clock runs) it
  // starts or continues the wait for k, applies the late policies, and sets
  // *until to when the caller should ask again at the latest (the next late
  // deadline, or 50 ms for STATUS, the STATE resend and stop) unless an
  // input comes first.
  bool Ready(int64_t k, bool state_sent, const std::function<void()>& publish_state, Clock::time_point* until);
  // Removes and returns the inputs for `step`, in controller id order, and
  // keeps their digest for STATE.
  std::vector<ControllerInput> Take(int64_t step);

  bool active() const { return lockstep_.active(); }
  uint64_t input_digest() const { return input_digest_; }  // of the inputs of the last step
  void DescribeInto(status_t* s) const;

 private:
  const LatePolicy late_policy_;  // for controllers registered without one
  const double late_timeout_;
  Lockstep lockstep_;
  uint64_t input_digest_ = 0;
  bool republish_state_ = false;  // a controller registered: it needs the current STATE
  bool waiting_ = false;
  Clock::time_point wait_start_;
  Clock::time_point last_state_;  // last STATE sent while waiting
};

// The input as applied, for the journal (a reused input carries its new step).
std::string EncodeInput(const ControllerInput& input);

}  // namespace contactsim
