// JSON text for the command-line tools' reports: a string as a quoted JSON
// string (RFC 8259, section 7: quote, backslash and control characters
// escaped). Header-only, so the tools and the benchmarks share it without a
// library of their own.
#pragma once

#include <cstdio>
#include <string>

namespace contactsim::tools {

inline std::string JsonQuote(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace contactsim::tools
