// A contact reduced to what the warm start keys and places it by, for the
// tests of warm_start_cache.h and persistent_contacts.h.
#pragma once

#include <cstdint>

#include "service/collision/contact.h"

namespace contactsim {
namespace testing {

inline Contact KeyedContact(BodyId a, BodyId b, uint32_t feature, const Vec3& point) {
  Contact c;
  c.id_a = a;
  c.id_b = b;
  c.feature_id = feature;
  c.point = point;
  return c;
}

}  // namespace testing
}  // namespace contactsim
