// The LCM transport: publishes raw bytes and delivers raw command payloads
// to a callback, so decoding (and its errors) stays in the server.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "service/server/transport.h"

namespace contactsim {

// The URL used when none is given and LCM_DEFAULT_URL is unset: LCM's own
// default group and port, ttl=0 (this host only), and an 8 MiB receive
// buffer so that a large STATE (1,000 bodies is ~113 kB in fragments) is not
// dropped by the kernel's small default buffer.
constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608";

// Commands LCM may queue per channel before the server handles them.
constexpr int kCommandQueueCapacity = 100000;

// explicit_url if not empty, else $LCM_DEFAULT_URL if set, else kDefaultLcmUrl.
std::string ResolveLcmUrl(const std::string& explicit_url);

class LcmTransport : public Transport {
 public:
  using RawHandler = std::function<void(const std::string& channel, const void* data, int size)>;

  explicit LcmTransport(const std::string& url);
  ~LcmTransport() override;
  bool good() const { return lcm_->good(); }
  void Publish(const std::string& channel, const void* data, int size) override;
  void Subscribe(const std::string& channel, RawHandler handler);
  // Dispatches received messages for up to timeout_ms; call from one thread.
  void HandleTimeout(int timeout_ms);

 private:
  class Relay;
  std::unique_ptr<lcm::LCM> lcm_;
  std::vector<std::unique_ptr<Relay>> relays_;
  // The udpm port with ttl=0, whose receive socket gets the own-datagram
  // filter (lcm_own_datagrams.h) once both LCM sockets exist: after the
  // first publish that follows a subscription. 0: none to install.
  int filter_port_ = 0;
  std::atomic<bool> filter_pending_{false};
};

}  // namespace contactsim
