// Plain binary writer and reader for engine caches that snapshots must carry
// (ContactMethod::SaveState / LoadState). Doubles are copied bit for bit, so
// a cache written and read back continues the run exactly. Little-endian
// host byte order: snapshots are for the machine type that wrote them
// (docs/snapshots.md).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include "service/physics/math.h"

namespace contactsim {

class ByteWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void PutVec3(const Vec3& v) {
    for (int i = 0; i < 3; ++i) Put(v[i]);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// Reads what ByteWriter wrote; every Get fails (returns false) once the
// bytes run out, so a truncated cache is reported, never read past.
class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool Get(T* value) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    if (bytes_.size() - pos_ < sizeof(T)) return false;
    std::memcpy(value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return true;
  }
  bool GetVec3(Vec3* v) { return Get(&v->x()) && Get(&v->y()) && Get(&v->z()); }
  bool done() const { return pos_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  size_t pos_ = 0;
};

}  // namespace contactsim
