#include "service/server/command_auth.h"

#include <utility>

namespace contactsim {

CommandAuthenticator::CommandAuthenticator(std::string key, double window_s, Clock clock, size_t max_clients)
    : key_(std::move(key)), window_s_(window_s), clock_(std::move(clock)), replay_(max_clients) {}

Status CommandAuthenticator::Admit(const std::string& channel, const void* data, int size, int* payload_size,
                                   uint64_t* seq) const {
  if (!HasSignatureTrailer(data, size)) {
    return Status::Unauthenticated("unsigned command on " + channel +
                                   ": commands must be signed (auth_key_file is set)");
  }
  const Verified verified = VerifySignature(key_, channel, data, size);
  if (!verified.ok) {
    return Status::Unauthenticated("forged command on " + channel +
                                   ": its signature does not match the server's key (another key, or "
                                   "altered on the way)");
  }
  std::string detail;
  if (!CheckFreshness(verified.seq, clock_(), window_s_, &detail)) {
    return Status::Unauthenticated("stale command on " + channel + ": " + detail +
                                   " (are the clocks of client and server in step?)");
  }
  *payload_size = verified.payload_size;
  *seq = verified.seq;
  return Status::Ok();
}

Status CommandAuthenticator::AcceptSequence(const std::string& client_id, uint64_t seq) {
  std::string why;
  if (replay_.Accept(client_id, seq, clock_(), window_s_, &why)) return Status::Ok();
  return Status::Unauthenticated(why + " (command from \"" + client_id + "\")");
}

}  // namespace contactsim
