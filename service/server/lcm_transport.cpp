#include "service/server/lcm_transport.h"

#include <spdlog/spdlog.h>

#include "service/server/lcm_own_datagrams.h"

#include <cstdlib>
#include <exception>

namespace contactsim {

std::string ResolveLcmUrl(const std::string& explicit_url) {
  if (!explicit_url.empty()) return explicit_url;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  if (env != nullptr && env[0] != '\0') return env;
  return kDefaultLcmUrl;
}

class LcmTransport::Relay {
 public:
  explicit Relay(RawHandler handler) : handler_(std::move(handler)) {}
  // A plain function, not a pointer to member: UBSan flags LCM's
  // pointer-to-member dispatch in lcm-cpp-impl.hpp.
  // The last guard of the LCM boundary: a handler that throws (it should
  // not: decoding answers every error) loses one message, not the server.
  static void Handle(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Relay* relay) {
    try {
      relay->handler_(channel, rbuf->data, static_cast<int>(rbuf->data_size));
    } catch (const std::exception& e) {
      spdlog::error("a message on {} was dropped: {}", channel, e.what());
    } catch (...) {
      spdlog::error("a message on {} was dropped: unknown exception", channel);
    }
  }

 private:
  RawHandler handler_;
};

LcmTransport::LcmTransport(const std::string& url) : lcm_(std::make_unique<lcm::LCM>(url)) {
  int port = 0, ttl = 0;
  if (ParseUdpmUrl(ResolveLcmUrl(url), &port, &ttl) && ttl == 0) filter_port_ = port;
}

LcmTransport::~LcmTransport() = default;

void LcmTransport::Publish(const std::string& channel, const void* data, int size) {
  lcm_->publish(channel, data, static_cast<unsigned>(size));
  if (filter_pending_.exchange(false)) {
    const Status st = FilterOwnDatagrams(filter_port_);
    if (st.ok()) {
      spdlog::debug("LCM: the server's own datagrams are filtered out of its receive socket");
    } else {
      spdlog::info("LCM: the server's own datagrams reach its receive socket ({})", st.message());
    }
  }
}

void LcmTransport::Subscribe(const std::string& channel, RawHandler handler) {
  relays_.push_back(std::make_unique<Relay>(std::move(handler)));
  lcm::Subscription* sub = lcm_->subscribeFunction(channel, &Relay::Handle, relays_.back().get());
  // LCM drops messages beyond 30 queued per subscription by default; a client
  // may send many commands without waiting, and every one must be answered.
  sub->setQueueCapacity(kCommandQueueCapacity);
  if (filter_port_ > 0 && relays_.size() == 1) filter_pending_ = true;
}

void LcmTransport::HandleTimeout(int timeout_ms) { lcm_->handleTimeout(timeout_ms); }

}  // namespace contactsim
