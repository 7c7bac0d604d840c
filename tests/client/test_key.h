// The HMAC key the client tests sign and verify with: 64 hex digits, the
// form a key file holds (docs/protocol.md, "Authentication").
#pragma once

#include <string>

namespace contactsim::testing {

inline const std::string kTestKey = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

}  // namespace contactsim::testing
