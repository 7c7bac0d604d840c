// What the decoders of Drake's driver commands share (arm_command.h,
// wsg_command.h): bytes from the network pass the size limit and the wire
// check of the encoding's bounds (wire_check.hpp) before the generated
// decoder runs, and whatever that decoder could throw becomes a status, as
// for the server's own channels (command_channels.h).
#pragma once

#include <contactsim/wire_check.hpp>

#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

// InvalidArgument naming field[i] and its value, for the first entry that is
// not a finite number.
Status CheckFiniteArray(const std::vector<double>& values, const char* field);
// InvalidArgument naming the field and its value when it is not finite.
Status CheckFiniteValue(double value, const char* field);

// Decodes an encoded `Msg` of at most max_bytes: sets *utime once the
// message could be read (to name it in a reply) and returns read(message),
// the protocol's own checks and copy. `type` names the message in errors.
template <typename Msg, typename Read>
Status DecodeDrakeCommand(const void* data, int size, int max_bytes, const char* type, int64_t* utime, Read read) {
  const std::string what = std::string(type) + " payload of " + std::to_string(size) + " bytes";
  if (size > max_bytes) {
    return Status::ResourceExhausted(what + " exceeds the limit of " + std::to_string(max_bytes) + " bytes");
  }
  std::string why;
  if (data == nullptr || !wire::Check<Msg>(data, size, &why)) {
    return Status::DecodeError("undecodable " + what + ": " + why);
  }
  try {
    Msg m{};  // the decoder fills every field; value-initialised for the compiler's sake
    if (m.decode(data, 0, size) != size) return Status::DecodeError("undecodable " + what);
    *utime = m.utime;
    return read(m);
  } catch (const std::bad_alloc&) {
    return Status::ResourceExhausted(what + ": out of memory while decoding");
  } catch (const std::exception& e) {
    return Status::DecodeError(what + ": " + e.what());
  }
}

}  // namespace contactsim
