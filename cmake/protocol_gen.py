#!/usr/bin/env python3
"""Generates contactsim/protocol.hpp: the protocol's channels, reply codes and
contact method names for the server and the C++ client.

The channels and method names come from lcmtypes/protocol.toml, the reply
codes from reply_t's constants (lcmtypes/reply_t.lcm), so that each is
declared once. The header includes no LCM code: the engine's Status takes
its codes from it.

    protocol_gen.py OUT.hpp protocol.toml FILE.lcm [FILE.lcm ...]
"""
import sys
from pathlib import Path

from lcm_schema import load_protocol, parse_lcm

PREAMBLE = """// Generated from lcmtypes/protocol.toml and reply_t.lcm by cmake/protocol_gen.py; do not edit.
#pragma once

#include <string_view>
"""

BODY = """
namespace contactsim {
namespace protocol {

// One channel, named <prefix>_<name>.
struct ChannelSpec {
  const char* name;
  const char* type_name;  // its LCM type
  bool incoming;          // clients to server
  bool replied;           // incoming: every command is answered on REPLY, otherwise only a refusal
  const char* published;  // outgoing: when the server sends it
};

struct ReplyCodeSpec {
  int value;
  const char* name;  // "OK", "INVALID_ARGUMENT", ...
};
"""

LOOKUP = """
// The channel named `name` (the suffix); null if the protocol has none.
constexpr const ChannelSpec* FindChannel(std::string_view name) {
  for (const ChannelSpec& c : kChannels) {
    if (name == c.name) return &c;
  }
  return nullptr;
}

// The name of reply code `value`; null for a code this build does not know.
constexpr const char* ReplyCodeName(int value) {
  for (const ReplyCodeSpec& c : kReplyCodes) {
    if (value == c.value) return c.name;
  }
  return nullptr;
}

}  // namespace protocol
}  // namespace contactsim
"""


def camel(upper):
    """BODY_CMD -> kBodyCmd."""
    return "k" + "".join(w.capitalize() for w in upper.split("_"))


def quoted(text):
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def main():
    out_path, table_path, lcm_files = sys.argv[1], sys.argv[2], sys.argv[3:]
    structs = {s.name: s for s in map(parse_lcm, lcm_files)}
    protocol = load_protocol(table_path, structs)
    codes = structs["reply_t"].constants
    out = [PREAMBLE]
    out.append("// X(kCamelName, UPPER_NAME, value) for each of reply_t's codes, to declare enums by.")
    out.append("#define CONTACTSIM_REPLY_CODES(X) \\")
    out += ["  X(%s, %s, %d) \\" % (camel(n), n, v) for n, v in codes]
    out.append("")
    out.append(BODY)
    out.append("// Each channel's name, the suffix after \"<prefix>_\".")
    out += ['inline constexpr char %s[] = "%s";' % (camel(c.name), c.name) for c in protocol.channels]
    out.append("\ninline constexpr ChannelSpec kChannels[] = {")
    out += ["    {%s, %s, %s, %s, %s}," % (camel(c.name), quoted(c.type), str(c.incoming).lower(),
                                          str(c.replied).lower(), quoted(c.published))
            for c in protocol.channels]
    out.append("};\n\ninline constexpr ReplyCodeSpec kReplyCodes[] = {")
    out += ['    {%d, "%s"},' % (v, n) for n, v in codes]
    out.append("};\n\n// The contact methods SET_METHOD names, in the server registry's order.")
    out.append("inline constexpr const char* kMethodNames[] = {%s};" % ", ".join(map(quoted, protocol.methods)))
    out.append(LOOKUP)
    Path(out_path).parent.mkdir(parents=True, exist_ok=True)
    Path(out_path).write_text("\n".join(out))


if __name__ == "__main__":
    main()
