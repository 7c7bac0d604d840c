#include "bench/tools/lockstep_bench/lcm_ping_pong.h"

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstring>
#include <vector>

namespace contactsim::bench {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The first 8 bytes of every ping and pong: the sequence number.
int64_t Sequence(const lcm::ReceiveBuffer* rbuf) {
  int64_t seq = -1;
  if (rbuf->data_size >= sizeof(seq)) std::memcpy(&seq, rbuf->data, sizeof(seq));
  return seq;
}

struct Pong {
  lcm::LCM* lc;
  std::string out;
  std::vector<uint8_t> payload;
  bool stop = false;
  Clock::time_point last = Clock::now();
  void OnPing(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    last = Clock::now();
    if (rbuf->data_size < sizeof(int64_t)) {
      stop = true;
      return;
    }
    const int64_t seq = Sequence(rbuf);
    std::memcpy(payload.data(), &seq, sizeof(seq));
    lc->publish(out, payload.data(), static_cast<unsigned>(payload.size()));
  }
};

struct Ping {
  int64_t awaited = -1;
  bool answered = false;
  void OnPong(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (Sequence(rbuf) == awaited) answered = true;  // a late pong of an earlier ping is ignored
  }
};

}  // namespace

int RunPong(const std::string& url, const std::string& channel, int pong_bytes, double idle_s) {
  lcm::LCM lc(url);
  if (!lc.good()) return 1;
  Pong pong{&lc, channel + "_PONG", std::vector<uint8_t>(std::max<int>(pong_bytes, 8))};
  lc.subscribe(channel + "_PING", &Pong::OnPing, &pong);
  while (!pong.stop && Since(pong.last) < idle_s) lc.handleTimeout(100);
  return 0;
}

bool RunPing(const std::string& url, const std::string& channel, int ping_bytes, double seconds, double ready_s,
             PingPongResult* result) {
  lcm::LCM lc(url);
  if (!lc.good()) return false;
  Ping ping;
  lc.subscribe(channel + "_PONG", &Ping::OnPong, &ping);
  std::vector<uint8_t> payload(std::max<int>(ping_bytes, 8));
  const std::string out = channel + "_PING";
  int64_t seq = 0;
  // one round trip: ping, wait for its pong, ping again after `timeout_s`
  auto round_trip = [&](double timeout_s, double give_up_s) {
    ping.awaited = ++seq;
    ping.answered = false;
    std::memcpy(payload.data(), &seq, sizeof(seq));
    const auto start = Clock::now();
    auto sent = start;
    lc.publish(out, payload.data(), static_cast<unsigned>(payload.size()));
    while (!ping.answered) {
      lc.handleTimeout(10);
      if (ping.answered) break;
      if (Since(start) > give_up_s) return false;
      if (Since(sent) > timeout_s) {
        ++result->resends;
        sent = Clock::now();
        lc.publish(out, payload.data(), static_cast<unsigned>(payload.size()));
      }
    }
    return true;
  };
  // the pong process may still be starting: its first answer is the go
  if (!round_trip(0.1, ready_s)) return false;
  for (int i = 0; i < 100; ++i) round_trip(1.0, ready_s);  // warm-up
  result->resends = 0;
  const auto start = Clock::now();
  while (Since(start) < seconds) {
    if (!round_trip(1.0, ready_s)) return false;
    ++result->round_trips;
  }
  result->seconds = Since(start);
  const uint8_t stop = 0;
  lc.publish(out, &stop, 1);  // shorter than a sequence number: stop
  return true;
}

}  // namespace contactsim::bench
