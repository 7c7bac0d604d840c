#include "service/server/step_requests.h"

#include <algorithm>

namespace contactsim {
namespace {

// Often enough for a client timeout of a second, rarely enough to cost
// nothing next to a step.
constexpr std::chrono::milliseconds kProgressPeriod{200};

}  // namespace

int64_t StepRequests::DoneOf(const Request& r, int64_t step) {
  return std::clamp<int64_t>(r.steps - (r.target_step - step), 0, r.steps);
}

void StepRequests::Add(const Command& cmd, int64_t step) {
  budget_ += cmd.steps;
  pending_.push_back({cmd.client_id, cmd.request_id, step + budget_, cmd.steps, Clock::now()});
  ReportProgress(step, true);  // accepted: the client may wait as long as progress comes
}

std::vector<StepRequests::Request> StepRequests::Done(int64_t step) {
  std::vector<Request> done;
  while (!pending_.empty() && pending_.front().target_step <= step) {
    done.push_back(std::move(pending_.front()));
    pending_.pop_front();
  }
  return done;
}

std::vector<StepRequests::Answer> StepRequests::Cancel(const std::string& why, int64_t step) {
  std::vector<Answer> answers;
  for (const Request& r : pending_) {
    answers.push_back({r.client_id, r.request_id,
                       Status::FailedPrecondition("step interrupted: " + why + " after " +
                                                  std::to_string(DoneOf(r, step)) + " of " + std::to_string(r.steps) +
                                                  " steps (at step " + std::to_string(step) + ")")});
  }
  pending_.clear();
  budget_ = 0;
  return answers;
}

void StepRequests::ReportProgress(int64_t step, bool now) {
  const auto t = Clock::now();
  if (pending_.empty() || (!now && t - last_progress_ < kProgressPeriod)) return;
  last_progress_ = t;
  for (const Request& r : pending_) {
    publisher_->Progress(r.client_id, r.request_id, "STEP", DoneOf(r, step), r.steps, step, r.accepted);
  }
}

void StepRequests::BeginRewind(const Command& cmd, int64_t from, int64_t to) {
  const auto now = Clock::now();
  rewinding_ = Rewinding{cmd.client_id, cmd.request_id, from, to, now, now};
  publisher_->Progress(cmd.client_id, cmd.request_id, "REWIND", 0, to - from, from, now);
}

void StepRequests::ReportRewindProgress(int64_t step) {
  if (!rewinding_) return;
  const auto t = Clock::now();
  if (t - rewinding_->last < kProgressPeriod) return;
  rewinding_->last = t;
  const Rewinding& r = *rewinding_;
  publisher_->Progress(r.client_id, r.request_id, "REWIND", std::max<int64_t>(0, step - r.from), r.to - r.from,
                       step, r.accepted);
}

}  // namespace contactsim
