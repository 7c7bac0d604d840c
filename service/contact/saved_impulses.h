// Kept contact impulses as snapshots carry them (ContactMethod::SaveState):
// WarmStartCache and PersistentContacts write the same bytes, so a snapshot
// reads back under either. Layout: the count, then each contact's body ids,
// feature id, impulses (normal, t1, t2 of the contact frame) and point.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "service/physics/byte_stream.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct SavedImpulse {
  BodyId a = 0, b = 0;
  uint32_t feature = 0;
  std::array<double, 3> lambda{};
  Vec3 point = Vec3::Zero();
};

inline void PutSavedImpulses(const std::vector<SavedImpulse>& saved, ByteWriter* out) {
  out->Put(static_cast<uint64_t>(saved.size()));
  for (const SavedImpulse& s : saved) {
    out->Put(s.a);
    out->Put(s.b);
    out->Put(s.feature);
    for (double l : s.lambda) out->Put(l);
    out->PutVec3(s.point);
  }
}

// Appends what PutSavedImpulses wrote (nothing when `in` is empty); false
// when the bytes run out.
inline bool GetSavedImpulses(ByteReader* in, std::vector<SavedImpulse>* saved) {
  uint64_t n = 0;
  if (in->done()) return true;
  bool ok = in->Get(&n);
  for (uint64_t i = 0; ok && i < n; ++i) {
    SavedImpulse s;
    ok = in->Get(&s.a) && in->Get(&s.b) && in->Get(&s.feature) && in->Get(&s.lambda[0]) && in->Get(&s.lambda[1]) &&
         in->Get(&s.lambda[2]) && in->GetVec3(&s.point);
    if (ok) saved->push_back(s);
  }
  return ok;
}

}  // namespace contactsim
