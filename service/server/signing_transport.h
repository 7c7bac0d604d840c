// A Transport that signs everything the server publishes (REPLY, STATE,
// CONTACTS, STATUS) before handing it to another transport, so clients with
// the key can tell the server's messages from anyone else's
// (docs/protocol.md, "Authentication"). One Signer for every channel: its
// seq increases across them all, and clients keep a window per channel.
#pragma once

#include <contactsim/signature.h>

#include <string>

#include "service/server/transport.h"

namespace contactsim {

class SigningTransport : public Transport {
 public:
  // `inner` must outlive this; `key` as LoadAuthKey gives it.
  SigningTransport(Transport* inner, std::string key);
  // Thread-safe as the Transport interface asks (the Signer locks its seq).
  void Publish(const std::string& channel, const void* data, int size) override;

 private:
  Transport* inner_;
  Signer signer_;
};

}  // namespace contactsim
