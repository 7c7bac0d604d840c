// Outcome of a command sent to contactsim-server: the server's reply_t code
// plus the client-side failures (no reply in time, LCM unusable), so that
// callers never need exceptions to learn what went wrong.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "contactsim/protocol.hpp"

namespace contactsim {

// Values >= 0 are reply_t's codes (lcmtypes/reply_t.lcm, through the
// generated protocol.hpp); negative values are decided by the client and
// never appear on the wire.
enum class ReplyCode : int32_t {
#define CONTACTSIM_CLIENT_REPLY_CODE(camel, upper, value) camel = value,
  CONTACTSIM_REPLY_CODES(CONTACTSIM_CLIENT_REPLY_CODE)
#undef CONTACTSIM_CLIENT_REPLY_CODE
  kTimeout = -1,    // no matching reply (or STATE) within the reply timeout
  kTransport = -2,  // LCM could not be opened or the publish failed
};

// "OK", "INVALID_ARGUMENT", ..., "TIMEOUT"; "UNKNOWN(<n>)" for a code this
// client does not know (a newer server).
std::string ReplyCodeName(ReplyCode code);

// One reply of the server (or a client-side failure).
struct CommandResult {
  ReplyCode code = ReplyCode::kOk;
  std::string message;        // the server's text, or the client's reason
  int64_t step = 0;           // step index at which the command took effect
  double time = 0.0;          // s, simulated time at that step
  std::vector<int64_t> ids;   // new body ids (ADD)
  int64_t request_id = 0;     // the request id the command was sent with

  bool ok() const { return code == ReplyCode::kOk; }
};

// "OK step=12 time=0.05 ids=[3]: added sphere" (for logs and the CLI).
std::string ToString(const CommandResult& result);
std::ostream& operator<<(std::ostream& os, const CommandResult& result);

// A command result that carries a value when it succeeded (e.g. the id of a
// new body). `value` is default-constructed when !ok().
template <typename T>
struct Result {
  CommandResult status;
  T value{};

  bool ok() const { return status.ok(); }
  ReplyCode code() const { return status.code; }
  const std::string& message() const { return status.message; }
};

// The first new id of an ADD reply (a body or a joint); an OK reply without
// one becomes kInternal.
Result<int64_t> WithNewId(CommandResult status);

}  // namespace contactsim
