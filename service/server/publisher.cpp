#include "service/server/publisher.h"

#include <contactsim/progress_t.hpp>
#include <contactsim/protocol.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unistd.h>

#include "service/server/messages.h"

namespace contactsim {

Publisher::Publisher(const ServerOptions& options, Transport* transport)
    : transport_(transport),
      prefix_(options.prefix),
      reply_(Channel(protocol::kReply)),
      state_(Channel(protocol::kState)),
      contacts_(Channel(protocol::kContacts)),
      status_(Channel(protocol::kStatus)),
      progress_(Channel(protocol::kProgress)),
      state_rate_hz_(options.state_rate_hz),
      contacts_rate_hz_(options.contacts_rate_hz),
      live_line_(options.live_line) {}

void Publisher::UpdateRates(double dt) {
  auto every = [dt](double rate) -> int64_t {
    if (rate <= 0.0) return 1;
    return std::max<int64_t>(1, std::llround(1.0 / (rate * dt)));
  };
  state_every_ = every(state_rate_hz_);
  contacts_every_ = every(contacts_rate_hz_);
}

void Publisher::State(const World& world, uint64_t input_digest) {
  state_t msg = MakeStateMessage(world);
  msg.input_digest = static_cast<int64_t>(input_digest);
  Publish(state_, msg);
  last_state_step_ = world.step;
}

void Publisher::Contacts(const World& world, const ContactSet& contacts, const ContactMethod& method) {
  Publish(contacts_, MakeContactsMessage(world, contacts, method));
}

void Publisher::Status(status_t s, Clock::time_point now) {
  const double elapsed = std::chrono::duration<double>(now - last_status_wall_).count();
  if (last_status_wall_ != Clock::time_point{} && elapsed > 0.0) {
    step_rate_ = (s.step - last_status_step_) / elapsed;
    measured_rtf_ = (s.time - last_status_time_) / elapsed;
  }
  last_status_wall_ = now;
  last_status_step_ = s.step;
  last_status_time_ = s.time;
  s.step_rate = step_rate_;
  s.real_time_factor = measured_rtf_;
  Publish(status_, s);
}

void Publisher::Progress(const std::string& client_id, int64_t request_id, const char* command, int64_t done,
                         int64_t total, int64_t step, Clock::time_point since) const {
  progress_t m;
  m.client_id = client_id;
  m.request_id = request_id;
  m.command = command;
  m.done = done;
  m.total = total;
  m.step = step;
  m.elapsed = std::chrono::duration<double>(Clock::now() - since).count();
  Publish(progress_, m);
}

void Publisher::LiveLine(bool final_line, const World& world, size_t contacts, const char* method, bool paused) {
  if (!live_line_) return;
  static const bool tty = isatty(fileno(stderr));
  const auto now = Clock::now();
  const auto period = tty ? std::chrono::milliseconds(250) : std::chrono::milliseconds(5000);
  if (!final_line && now - last_live_line_ < period) return;
  last_live_line_ = now;
  std::fprintf(stderr, "%sstep %8lld  t %9.3f s  rtf %5.2f  bodies %5zu  contacts %5zu  %-8s %s%s",
               tty ? "\r\033[K" : "", static_cast<long long>(world.step), world.time, measured_rtf_,
               world.bodies().size(), contacts, method, paused ? "paused" : "running", tty && !final_line ? "" : "\n");
  std::fflush(stderr);
}

}  // namespace contactsim
