// A raw LCM ping-pong between two processes: the transport's own limit for
// a lockstep cycle. One lockstep cycle is a STATE (server -> controller)
// answered by an INPUT (controller -> server); a round trip here is a ping
// of the STATE's size answered by a pong of the INPUT's size, on the same
// kind of URL, with no decoding, physics or bookkeeping in between.
#pragma once

#include <cstdint>
#include <string>

namespace contactsim::bench {

struct PingPongResult {
  int64_t round_trips = 0;
  int64_t resends = 0;     // pings with no pong within the timeout (UDP loss)
  double seconds = 0.0;
  double per_second() const { return seconds > 0.0 ? round_trips / seconds : 0.0; }
};

// The pong side (its own process): answers every ping on <channel>_PING with
// `pong_bytes` on <channel>_PONG carrying the ping's sequence number; returns
// on a ping shorter than 8 bytes (stop) or after `idle_s` without pings.
int RunPong(const std::string& url, const std::string& channel, int pong_bytes, double idle_s);

// The ping side: waits for the pong process to answer (pinging every 0.1 s,
// up to `ready_s`), then measures round trips with `ping_bytes` pings for
// `seconds`; a ping unanswered after 1 s is sent again. Sends the stop ping
// at the end. False if the pong never answered.
bool RunPing(const std::string& url, const std::string& channel, int ping_bytes, double seconds, double ready_s,
             PingPongResult* result);

}  // namespace contactsim::bench
