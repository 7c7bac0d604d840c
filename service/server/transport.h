// Where the server's messages go. The real implementation is LCM
// (lcm_transport.h); tests use a recording mock, so the command and step
// logic is tested without a network (as Drake's DrakeLcmInterface).
#pragma once

#include <string>

namespace contactsim {

class Transport {
 public:
  virtual ~Transport() = default;
  // Must be safe to call from the LCM and the simulation thread at once.
  virtual void Publish(const std::string& channel, const void* data, int size) = 0;
};

}  // namespace contactsim
