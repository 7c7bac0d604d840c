// SimServer's progress reports for long commands (docs/protocol.md, "Long
// commands"): a client's reply timeout counts from the last sign of work,
// so a STEP of thousands of steps on a slow method, or a REWIND far back,
// is not mistaken for a dead server. Simulation thread.
#include <contactsim/progress_t.hpp>

#include <algorithm>

#include "service/server/sim_server.h"

namespace contactsim {
namespace {

// Often enough for a client timeout of a second, rarely enough to cost
// nothing next to a step.
constexpr std::chrono::milliseconds kProgressPeriod{200};

}  // namespace

void SimServer::PublishProgress(const std::string& client_id, int64_t request_id, const char* command, int64_t done,
                                int64_t total, std::chrono::steady_clock::time_point since) {
  progress_t m;
  m.client_id = client_id;
  m.request_id = request_id;
  m.command = command;
  m.done = done;
  m.total = total;
  m.step = world_.step;
  m.elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
  const int n = m.getEncodedSize();
  std::vector<uint8_t> buf(n);
  m.encode(buf.data(), 0, n);
  transport_->Publish(Channel("PROGRESS"), buf.data(), n);
}

void SimServer::ReportStepProgress(bool now) {
  const auto t = std::chrono::steady_clock::now();
  if (pending_steps_.empty() || (!now && t - last_progress_ < kProgressPeriod)) return;
  last_progress_ = t;
  for (const PendingStep& p : pending_steps_) {
    const int64_t done = std::clamp<int64_t>(p.steps - (p.target_step - world_.step), 0, p.steps);
    PublishProgress(p.client_id, p.request_id, "STEP", done, p.steps, p.accepted);
  }
}

void SimServer::ReportRewindProgress() {
  const auto t = std::chrono::steady_clock::now();
  if (!rewinding_ || t - rewinding_->last < kProgressPeriod) return;
  rewinding_->last = t;
  const Rewinding& r = *rewinding_;
  PublishProgress(r.client_id, r.request_id, "REWIND", std::max<int64_t>(0, world_.step - r.from), r.to - r.from,
                  r.accepted);
}

}  // namespace contactsim
