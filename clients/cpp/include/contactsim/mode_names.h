// The run modes' names by their wire value (status_t::mode, scene_cmd_t::mode),
// the C++ client's one table of them: contactsim-ctl prints a STATUS with it.
// The names are the server's (kRunModeNames, service/server/command.h), which
// a client may not include; tests/python/test_mode_names.py holds this table,
// the server's and the Python client's (state.MODE_NAMES) to one another.
#pragma once

#include <cstdint>

#include "contactsim/status_t.hpp"

namespace contactsim {

struct ModeName {
  int8_t mode;
  const char* name;
};

inline constexpr ModeName kModeNames[] = {{status_t::REALTIME, "realtime"},
                                          {status_t::FREE_RUN, "free_run"},
                                          {status_t::LOCKSTEP, "lockstep"}};

// The name of a mode value; "unknown" for a value no table row has.
inline const char* NameOfMode(int8_t mode) {
  for (const ModeName& m : kModeNames) {
    if (m.mode == mode) return m.name;
  }
  return "unknown";
}

}  // namespace contactsim
