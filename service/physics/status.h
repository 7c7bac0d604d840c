// Status values returned by the engine instead of exceptions. The server
// turns them into replies (reply_t codes) and log lines.
#pragma once

#include <string>
#include <utility>

#include <contactsim/protocol.hpp>

namespace contactsim {

// reply_t's codes (lcmtypes/reply_t.lcm, through the generated
// protocol.hpp), so that a status becomes a reply code by a cast.
enum class StatusCode {
#define CONTACTSIM_STATUS_CODE(camel, upper, value) camel = value,
  CONTACTSIM_REPLY_CODES(CONTACTSIM_STATUS_CODE)
#undef CONTACTSIM_STATUS_CODE
};

class Status {
 public:
  Status() = default;
  static Status Ok() { return Status(); }
  static Status InvalidArgument(std::string message) {
    return Status(StatusCode::kInvalidArgument, std::move(message));
  }
  static Status NotFound(std::string message) { return Status(StatusCode::kNotFound, std::move(message)); }
  static Status FailedPrecondition(std::string message) {
    return Status(StatusCode::kFailedPrecondition, std::move(message));
  }
  static Status DecodeError(std::string message) { return Status(StatusCode::kDecodeError, std::move(message)); }
  static Status Internal(std::string message) { return Status(StatusCode::kInternal, std::move(message)); }
  static Status Unauthenticated(std::string message) {
    return Status(StatusCode::kUnauthenticated, std::move(message));
  }
  static Status ResourceExhausted(std::string message) {
    return Status(StatusCode::kResourceExhausted, std::move(message));
  }

  // The same code with `prefix` before the message.
  Status Prefixed(const std::string& prefix) const { return Status(code_, prefix + message_); }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

}  // namespace contactsim
