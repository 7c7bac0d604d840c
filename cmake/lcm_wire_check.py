#!/usr/bin/env python3
"""Generates wire_check.hpp: a bounds check for every LCM type in lcmtypes/.

lcm-gen's C++ decoders trust the length and count fields they read: a
string whose length field is 0 or negative, or an array count of two
billion, makes them call std::string::assign or std::vector::resize with a
huge size before any byte is checked (std::length_error, std::bad_alloc, or
the kernel's OOM killer). The checks generated here walk the same encoding
(LCM's type specification: big-endian fields in declaration order, strings as
int32 length including the NUL, then the bytes) without allocating, and
accept a payload only when every length and count fits in the bytes that
remain and the message ends exactly where the payload does. A payload that
passes is safe to hand to the generated decode.

    lcm_wire_check.py OUT.hpp FILE.lcm [FILE.lcm ...]
"""
import sys

from lcm_schema import parse_lcm

PRIMITIVE_BYTES = {
    "int8_t": 1, "byte": 1, "boolean": 1, "int16_t": 2, "int32_t": 4,
    "int64_t": 8, "float": 4, "double": 8,
}
INTEGER_TYPES = {"int8_t", "int16_t", "int32_t", "int64_t", "byte"}


def min_bytes(ftype, structs):
    """The fewest bytes one element of ftype can take."""
    if ftype in PRIMITIVE_BYTES:
        return PRIMITIVE_BYTES[ftype]
    if ftype == "string":
        return 5  # int32 length + the NUL
    total = 0
    for t, _, dims in structs[ftype]:
        n = 1
        for d in dims:
            n = n * int(d) if d.isdigit() else 0
        total += n * min_bytes(t, structs)
    return total


def emit_field(ftype, name, dims, structs, out):
    count = " * ".join(d if d.isdigit() else f"v_{d}" for d in dims) or "1"
    label = f'"{name}"'
    if ftype in PRIMITIVE_BYTES:
        size = PRIMITIVE_BYTES[ftype]
        if not dims and ftype in INTEGER_TYPES:
            out.append(f"  int64_t v_{name} = 0;")
            out.append(f"  if (!r.Int({size}, &v_{name}, {label})) return false;")
        else:
            out.append(f"  if (!r.Array({count}, {size}, {label})) return false;")
        return
    check = f"r.String({label})" if ftype == "string" else f"CheckFields_{ftype}(r)"
    if not dims:
        out.append(f"  if (!{check}) return false;")
        return
    per = min_bytes(ftype, structs)
    out.append(f"  if (!r.Fits({count}, {per}, {label})) return false;")
    out.append(f"  for (int64_t i = 0; i < {count}; ++i) {{")
    out.append(f"    if (!{check}) return false;")
    out.append("  }")


PREAMBLE = r'''// Generated from lcmtypes/*.lcm by cmake/lcm_wire_check.py; do not edit.
// wire::Check<Msg>(data, size, &why) is true when the payload is a complete
// encoding of Msg whose every length and count fits in its bytes, so that
// Msg::decode can neither over-allocate nor throw on it.
#pragma once

#include <cstdint>
#include <string>

namespace contactsim {
namespace wire {

// A cursor over big-endian LCM bytes that never reads past the end and
// names the field that does not fit.
class Reader {
 public:
  Reader(const void* data, int size, std::string* why)
      : p_(static_cast<const uint8_t*>(data)), left_(size < 0 ? 0 : size), why_(why) {}
  int64_t left() const { return left_; }
  bool Int(int bytes, int64_t* v, const char* field) {
    if (!Need(bytes, field)) return false;
    uint64_t u = 0;
    for (int i = 0; i < bytes; ++i) u = (u << 8) | p_[i];
    if (bytes < 8 && (u >> (8 * bytes - 1)) != 0) u |= ~uint64_t{0} << (8 * bytes);  // sign-extend
    *v = static_cast<int64_t>(u);
    Advance(bytes);
    return true;
  }
  // `count` elements of at least `bytes` each must fit in what remains.
  bool Fits(int64_t count, int64_t bytes, const char* field) {
    if (count < 0) return Fail(std::string(field) + ": negative count " + std::to_string(count));
    if (bytes > 0 && count > left_ / bytes) {
      return Fail(std::string(field) + ": count " + std::to_string(count) + " of " + std::to_string(bytes) +
                  "-byte elements, but only " + std::to_string(left_) + " bytes remain");
    }
    return true;
  }
  bool Array(int64_t count, int64_t bytes, const char* field) {
    if (!Fits(count, bytes, field)) return false;
    Advance(count * bytes);
    return true;
  }
  bool String(const char* field) {
    int64_t len = 0;
    if (!Int(4, &len, field)) return false;
    if (len < 1) return Fail(std::string(field) + ": string length " + std::to_string(len) + " (must count its NUL)");
    if (!Need(len, field)) return false;
    if (p_[len - 1] != 0) return Fail(std::string(field) + ": string does not end in NUL");
    Advance(len);
    return true;
  }
  bool Fail(const std::string& what) {
    if (why_ != nullptr && why_->empty()) *why_ = what;
    return false;
  }

 private:
  bool Need(int64_t n, const char* field) {
    if (n <= left_) return true;
    return Fail(std::string(field) + ": needs " + std::to_string(n) + " bytes, " + std::to_string(left_) +
                " remain");
  }
  void Advance(int64_t n) {
    p_ += n;
    left_ -= n;
  }
  const uint8_t* p_;
  int64_t left_;
  std::string* why_;
};

template <typename Msg>
bool Check(const void* data, int size, std::string* why);
'''


def main():
    out_path, files = sys.argv[1], sys.argv[2:]
    structs, packages = {}, {}
    for f in sorted(files):
        s = parse_lcm(f)
        structs[s.name], packages[s.name] = s.fields, s.package
    out = [PREAMBLE]
    for name in structs:
        out.append(f"inline bool CheckFields_{name}(Reader& r);")
    for name, fields in structs.items():
        out.append(f"\ninline bool CheckFields_{name}(Reader& r) {{")
        for ftype, fname, dims in fields:
            emit_field(ftype, fname, dims, structs, out)
        for ftype, fname, dims in fields:
            if not dims and ftype in INTEGER_TYPES:
                out.append(f"  (void)v_{fname};")
        out.append("  return true;\n}")
    out.append("\n}  // namespace wire\n}  // namespace contactsim\n")
    # the specialisations need the generated types for their hashes
    for name in structs:
        out.append(f'#include "{packages[name]}/{name}.hpp"')
    out.append("\nnamespace contactsim {\nnamespace wire {")
    for name in structs:
        cls = f"::{packages[name]}::{name}"
        out.append(f"""
template <>
inline bool Check<{cls}>(const void* data, int size, std::string* why) {{
  Reader r(data, size, why);
  int64_t hash = 0;
  if (!r.Int(8, &hash, "fingerprint")) return false;
  if (hash != {cls}::getHash()) return r.Fail("fingerprint is not {name}'s");
  if (!CheckFields_{name}(r)) return false;
  if (r.left() != 0) return r.Fail(std::to_string(r.left()) + " bytes after the end of {name}");
  return true;
}}""")
    out.append("\n}  // namespace wire\n}  // namespace contactsim")
    with open(out_path, "w") as fh:
        fh.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
