// 64-bit FNV-1a (Fowler, Noll, Vo) over bit patterns: the world's state hash
// and the lockstep input digest. -0.0 hashes as +0.0, since both describe
// the same state.
#pragma once

#include <cstddef>
#include <cstdint>

#include "service/physics/math.h"

namespace contactsim {

struct Fnv1a {
  uint64_t h = 1469598103934665603ull;
  void Bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
  void Double(double d) {
    if (d == 0.0) d = 0.0;
    Bytes(&d, sizeof d);
  }
  void Vector(const Vec3& v) {
    for (int i = 0; i < 3; ++i) Double(v[i]);
  }
};

}  // namespace contactsim
