// The steps the world owes its clients: STEP commands in flight (each is
// answered when its last step is done), the budget of steps a paused world
// still takes for them, and the REWIND being re-simulated; with their
// PROGRESS reports, so that a client's reply timeout counts from the last
// sign of work (docs/protocol.md, "Long commands"). Simulation thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "service/physics/status.h"
#include "service/server/command.h"
#include "service/server/publisher.h"

namespace contactsim {

class StepRequests {
 public:
  using Clock = std::chrono::steady_clock;

  // A STEP in flight.
  struct Request {
    std::string client_id;
    int64_t request_id;
    int64_t target_step;
    int64_t steps;  // asked for: the first is target_step - steps + 1
    Clock::time_point accepted;
  };
  // An answer the server owes a client.
  struct Answer {
    std::string client_id;
    int64_t request_id;
    Status status;
  };

  explicit StepRequests(const Publisher* publisher) : publisher_(publisher) {}

  // A STEP of cmd.steps accepted at `step`: it ends at the step the budget
  // then reaches, and reports its progress at once.
  void Add(const Command& cmd, int64_t step);
  // Steps still owed (a paused world takes them).
  bool owed() const { return budget_ > 0; }
  // One step taken.
  void Took() {
    if (budget_ > 0) --budget_;
  }
  // The STEPs whose last step is done at `step`, oldest first; they are forgotten.
  std::vector<Request> Done(int64_t step);
  // Every STEP in flight, answered as interrupted by `why` at `step`; the budget is dropped.
  std::vector<Answer> Cancel(const std::string& why, int64_t step);
  // PROGRESS of every STEP in flight, at most every kProgressPeriod unless `now`.
  void ReportProgress(int64_t step, bool now);

  // A REWIND of `cmd` re-simulating from step `from` to `to`.
  void BeginRewind(const Command& cmd, int64_t from, int64_t to);
  void ReportRewindProgress(int64_t step);  // at most every kProgressPeriod
  void EndRewind() { rewinding_.reset(); }

 private:
  // Steps of `r` taken when the world is at `step`.
  static int64_t DoneOf(const Request& r, int64_t step);

  const Publisher* publisher_;
  std::deque<Request> pending_;
  int64_t budget_ = 0;
  Clock::time_point last_progress_{};
  struct Rewinding {
    std::string client_id;
    int64_t request_id;
    int64_t from, to;  // steps
    Clock::time_point accepted, last;
  };
  std::optional<Rewinding> rewinding_;
};

}  // namespace contactsim
