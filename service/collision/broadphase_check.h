// Always-on check of the broadphase input: one movable flag per box. A
// mismatch is a programmer error (docs/architecture.md, errors), so it
// aborts with a message rather than reading out of bounds.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "service/collision/aabb.h"

namespace contactsim {

inline void CheckBroadphaseInput(const std::vector<Aabb>& boxes, const std::vector<bool>& movable) {
  if (boxes.size() != movable.size()) {
    std::fprintf(stderr, "broadphase: %zu boxes but %zu movable flags\n", boxes.size(), movable.size());
    std::abort();
  }
}

}  // namespace contactsim
