// What the server sends, on the channels it publishes: one
// encode-and-publish path for every message, STATE and CONTACTS decimated to
// their rates of simulated time, STATUS with the step rate and real-time
// factor measured between two of them, PROGRESS of long commands, and the
// live line on stderr. Replies may go out from either thread (the
// transport's Publish is thread-safe; nothing here that a reply touches
// changes after construction); the rest belongs to the thread that holds
// the loop's turn (sim_server.h).
#pragma once

#include <contactsim/contacts_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/state_t.hpp>
#include <contactsim/status_t.hpp>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"
#include "service/server/server_options.h"
#include "service/server/transport.h"

namespace contactsim {

class Publisher {
 public:
  using Clock = std::chrono::steady_clock;

  Publisher(const ServerOptions& options, Transport* transport);

  // <prefix>_<suffix>
  std::string Channel(const char* suffix) const { return prefix_ + "_" + suffix; }

  // The one path from a message to the wire.
  template <typename Msg>
  void Publish(const std::string& channel, const Msg& msg) const {
    const int n = msg.getEncodedSize();
    std::vector<uint8_t> buf(n);
    msg.encode(buf.data(), 0, n);
    transport_->Publish(channel, buf.data(), n);
  }

  void Reply(const reply_t& reply) const { Publish(reply_, reply); }

  // STATE and CONTACTS every so many steps: the configured rates of
  // simulated time at the world's time step (0 Hz = every step).
  void UpdateRates(double dt);
  bool StateDue(int64_t step) const { return step % state_every_ == 0; }
  bool ContactsDue(int64_t step) const { return step % contacts_every_ == 0; }
  // True when the last STATE sent was of `step`.
  bool StateSentAt(int64_t step) const { return last_state_step_ == step; }

  void State(const World& world, uint64_t input_digest);
  void Contacts(const World& world, const ContactSet& contacts, const ContactMethod& method);
  // Adds the step rate and real-time factor measured since the last STATUS
  // to `s` (filled by the server with the rest) and sends it.
  void Status(status_t s, Clock::time_point now);
  // One PROGRESS of a long command (docs/protocol.md, "Long commands").
  void Progress(const std::string& client_id, int64_t request_id, const char* command, int64_t done, int64_t total,
                int64_t step, Clock::time_point since) const;
  // The one-line report on stderr, at most 4 times a second on a terminal
  // (every 5 s otherwise), unless `final_line`; nothing without live_line.
  void LiveLine(bool final_line, const World& world, size_t contacts, const char* method, bool paused);

 private:
  Transport* transport_;
  const std::string prefix_;
  const std::string reply_, state_, contacts_, status_, progress_;  // the full channel names
  const double state_rate_hz_, contacts_rate_hz_;
  const bool live_line_;

  int64_t state_every_ = 1, contacts_every_ = 1;
  int64_t last_state_step_ = -1;
  // where the last STATUS left the measured rates
  Clock::time_point last_status_wall_{};  // none yet: the first STATUS only sets the base
  int64_t last_status_step_ = 0;
  double last_status_time_ = 0.0;
  double step_rate_ = 0.0, measured_rtf_ = 0.0;
  Clock::time_point last_live_line_;
};

}  // namespace contactsim
