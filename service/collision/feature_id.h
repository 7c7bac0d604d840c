// Feature ids of contact points. A point's id is a 32-bit FNV-1a hash of the
// indices of the features that produced it (reference face, incident face,
// clip plane, vertex, edge), so that the same features give the same id from
// one step to the next and a solver can warm-start from last step's impulse.
#pragma once

#include <cstdint>
#include <initializer_list>

namespace contactsim {

inline uint32_t FeatureId(std::initializer_list<uint32_t> parts) {
  uint32_t hash = 2166136261u;  // FNV-1a offset basis
  for (uint32_t part : parts) {
    for (int byte = 0; byte < 4; ++byte) {
      hash ^= (part >> (8 * byte)) & 0xffu;
      hash *= 16777619u;  // FNV-1a prime
    }
  }
  return hash;
}

}  // namespace contactsim
