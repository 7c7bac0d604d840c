// What applying one command did: the reply's status and text, the new ids,
// and whether the world's content changed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

struct Outcome {
  Status status;
  std::string message;       // the reply's text when the status is OK
  std::vector<int64_t> ids;  // ADD: the new id
  bool changed = false;      // the world's content changed
  bool deferred = false;     // answered later (STEP when its last step is done; an accepted input by its STATE)

  static Outcome Done(std::string message, bool changed) {
    Outcome o;
    o.message = std::move(message);
    o.changed = changed;
    return o;
  }
  static Outcome Failed(Status status) {
    Outcome o;
    o.status = std::move(status);
    return o;
  }
};

}  // namespace contactsim
