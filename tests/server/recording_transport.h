// A transport that records every published message (as DrakeMockLcm does),
// so the server logic is tested without a network, and the LCM encoding
// helper the server tests share.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "service/server/transport.h"

namespace contactsim {
namespace testing {

class RecordingTransport : public Transport {
 public:
  void Publish(const std::string& channel, const void* data, int size) override {
    const auto* p = static_cast<const uint8_t*>(data);
    messages.push_back({channel, std::vector<uint8_t>(p, p + size)});
  }
  template <typename T>
  std::vector<T> All(const std::string& channel) const {
    std::vector<T> out;
    for (const auto& [ch, bytes] : messages) {
      if (ch != channel) continue;
      T msg;
      msg.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
      out.push_back(msg);
    }
    return out;
  }
  std::vector<std::pair<std::string, std::vector<uint8_t>>> messages;
};

template <typename T>
std::vector<uint8_t> Encode(const T& msg) {
  std::vector<uint8_t> buf(msg.getEncodedSize());
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

}  // namespace testing
}  // namespace contactsim
