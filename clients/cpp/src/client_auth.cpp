#include "client_auth.h"

#include <utility>

namespace contactsim {

ClientAuth::ClientAuth(std::string key, double window_s)
    : key_(std::move(key)), window_s_(window_s), signer_(key_) {}

std::string ClientAuth::Sign(const std::string& channel, const void* data, int size) {
  return signer_.Sign(channel, data, size);
}

int ClientAuth::Unwrap(const std::string& channel, const void* data, int size) {
  const Verified verified = VerifySignature(key_, channel, data, size);
  std::string why = verified.error;
  if (verified.ok && replay_.Accept(channel, verified.seq, WallClockNanoseconds(), window_s_, &why)) {
    return verified.payload_size;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  ++failures_;
  last_failure_ = channel + ": " + why;
  return -1;
}

uint64_t ClientAuth::failures() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failures_;
}

std::string ClientAuth::last_failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return last_failure_;
}

}  // namespace contactsim
