// The client's side of signed messages (docs/protocol.md, "Authentication"):
// signs what the client publishes and checks what the server publishes
// (mac, freshness, and replay keyed by channel), counting and explaining
// what it drops. Private to contactsim::Client; thread-safe.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>

#include "contactsim/signature.h"

namespace contactsim {

class ClientAuth {
 public:
  ClientAuth(std::string key, double window_s);
  // payload followed by its trailer
  std::string Sign(const std::string& channel, const void* data, int size);
  // The payload size of a verified server message, or -1 when it is
  // dropped (counted; the reason kept).
  int Unwrap(const std::string& channel, const void* data, int size);
  uint64_t failures() const;
  std::string last_failure() const;  // "<channel>: <why>", "" before any

 private:
  const std::string key_;
  const double window_s_;
  Signer signer_;
  ReplayWindow replay_;  // one "sender" per channel: the server signs them all
  mutable std::mutex mutex_;  // guards the two below
  uint64_t failures_ = 0;
  std::string last_failure_;
};

}  // namespace contactsim
