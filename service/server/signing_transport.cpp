#include "service/server/signing_transport.h"

#include <utility>

namespace contactsim {

SigningTransport::SigningTransport(Transport* inner, std::string key) : inner_(inner), signer_(std::move(key)) {}

void SigningTransport::Publish(const std::string& channel, const void* data, int size) {
  const std::string message = signer_.Sign(channel, data, size);
  inner_->Publish(channel, message.data(), static_cast<int>(message.size()));
}

}  // namespace contactsim
