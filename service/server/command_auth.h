// The server's gate for signed commands (docs/protocol.md, "Authentication").
// With an auth key, a command reaches the decoder only when its trailer is
// present (else "unsigned"), its mac matches (else "forged") and its seq is
// within the window of the server's clock (else "stale"); once decoded, its
// seq must be new for its client_id (else "replayed"). The split follows the
// order of the receive path: the client id is known only after decoding,
// and nothing unauthenticated should reach the decoder.
//
// Runs on the LCM thread; the refusal is a Status (kUnauthenticated) that
// the server turns into a reply. Nothing throws.
#pragma once

#include <contactsim/signature.h>

#include <cstdint>
#include <functional>
#include <string>

#include "service/physics/status.h"

namespace contactsim {

class CommandAuthenticator {
 public:
  using Clock = std::function<uint64_t()>;  // ns since the Unix epoch

  // `key` as LoadAuthKey gives it; `window_s` (> 0) bounds |seq - now|.
  CommandAuthenticator(std::string key, double window_s = kDefaultAuthWindowSeconds,
                       Clock clock = WallClockNanoseconds,
                       size_t max_clients = kDefaultMaxReplaySenders);

  // Checks the trailer, the mac and the freshness of a message received on
  // `channel`; on success the payload (the LCM encoding) is the first
  // *payload_size bytes of `data` and *seq is its signed seq.
  Status Admit(const std::string& channel, const void* data, int size, int* payload_size, uint64_t* seq) const;
  // Refuses a seq already accepted from `client_id` (or more than 64 below
  // its newest); remembers the ones it accepts.
  Status AcceptSequence(const std::string& client_id, uint64_t seq);

  double window_s() const { return window_s_; }

 private:
  const std::string key_;
  const double window_s_;
  const Clock clock_;
  ReplayWindow replay_;
};

}  // namespace contactsim
