// Commands per second per client: a token bucket for each client id (rate r
// tokens a second, at most `burst` saved up; a command takes one). Keeps
// one client's flood from filling the inbox ahead of everyone else's
// commands. Client ids are the senders' own words, so the table is bounded:
// when it is full, buckets that have refilled (they hold no history) are
// dropped, and clients that still find no room share one overflow bucket,
// so inventing new ids buys no extra rate.
#pragma once

#include <chrono>
#include <string>
#include <unordered_map>

namespace contactsim {

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  // rate <= 0: no limit.
  RateLimiter(double rate, double burst, size_t max_clients = 4096);

  // True if `client` may send one more command at `now` (and takes it).
  bool Admit(const std::string& client, Clock::time_point now);
  size_t tracked() const { return buckets_.size(); }

 private:
  struct Bucket {
    double tokens;
    Clock::time_point last;
  };
  bool Take(Bucket* b, Clock::time_point now);
  void DropRefilled(Clock::time_point now);

  double rate_, burst_;
  size_t max_clients_;
  std::unordered_map<std::string, Bucket> buckets_;
  Bucket overflow_;
  Clock::time_point last_sweep_{};
};

}  // namespace contactsim
