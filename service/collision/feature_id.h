// Feature ids of contact points. A point's id is a 32-bit FNV-1a hash of the
// indices of the features that produced it (reference face, incident face,
// clip plane, vertex, edge), so that the same features give the same id from
// one step to the next and a solver can warm-start from last step's impulse.
#pragma once

#include <cstdint>
#include <initializer_list>

namespace contactsim {

// One byte of FNV-1a.
inline uint32_t FnvByte(uint32_t hash, uint32_t byte) {
  return (hash ^ (byte & 0xffu)) * 16777619u;  // FNV-1a prime
}

// The id of the parts hashed into `hash` followed by `part`: FNV-1a has no
// finalisation, so FeatureIdAppend(FeatureId({p1, p2}), p3) is
// FeatureId({p1, p2, p3}), and ids sharing their first parts hash them once.
inline uint32_t FeatureIdAppend(uint32_t hash, uint32_t part) {
  // the four bytes, lowest first, spelled out: the loop over them with a
  // variable shift was a third of clipping a box face
  hash = FnvByte(hash, part);
  hash = FnvByte(hash, part >> 8);
  hash = FnvByte(hash, part >> 16);
  return FnvByte(hash, part >> 24);
}

inline uint32_t FeatureId(std::initializer_list<uint32_t> parts) {
  uint32_t hash = 2166136261u;  // FNV-1a offset basis
  for (uint32_t part : parts) hash = FeatureIdAppend(hash, part);
  return hash;
}

}  // namespace contactsim
