// What each contact method can simulate, in one table, so that a world a
// method cannot step is refused with a status instead of being stepped
// wrongly: the barrier method (IPC on affine bodies, barrier/) has no
// joint constraints, and stepping a jointed world with it would drop them
// silently. The server asks before it adds a joint, switches the method or
// loads a scene.
#pragma once

#include <string>

#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

// True when the method named `method` simulates joints.
bool MethodSupportsJoints(const std::string& method);

// Ok when the method can step `world`; else FailedPrecondition naming the
// method and what it cannot simulate ("... does not simulate joints ...").
Status CheckMethodSupports(const std::string& method, const World& world);

}  // namespace contactsim
