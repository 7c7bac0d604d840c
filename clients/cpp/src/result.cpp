// Names and printing of client-side command results.
#include "contactsim/result.h"

#include <sstream>
#include <utility>

namespace contactsim {

std::string ReplyCodeName(ReplyCode code) {
  if (code == ReplyCode::kTimeout) return "TIMEOUT";
  if (code == ReplyCode::kTransport) return "TRANSPORT";
  if (const char* name = protocol::ReplyCodeName(static_cast<int32_t>(code))) return name;
  // A newer server may send a code this client was not built with.
  return "UNKNOWN(" + std::to_string(static_cast<int32_t>(code)) + ")";
}

std::string ToString(const CommandResult& result) {
  std::ostringstream os;
  os << ReplyCodeName(result.code);
  if (result.code != ReplyCode::kTimeout &&
      result.code != ReplyCode::kTransport) {
    os << " step=" << result.step << " time=" << result.time;
  }
  if (!result.ids.empty()) {
    os << " ids=[";
    for (size_t i = 0; i < result.ids.size(); ++i) {
      os << (i ? "," : "") << result.ids[i];
    }
    os << "]";
  }
  if (!result.message.empty()) os << ": " << result.message;
  return os.str();
}

std::ostream& operator<<(std::ostream& os, const CommandResult& result) {
  return os << ToString(result);
}

Result<int64_t> WithNewId(CommandResult status) {
  Result<int64_t> result;
  if (status.ok() && status.ids.empty()) {
    status.code = ReplyCode::kInternal;
    status.message = "ADD replied OK without a new id: " + status.message;
  }
  if (status.ok()) result.value = status.ids.front();
  result.status = std::move(status);
  return result;
}

}  // namespace contactsim
