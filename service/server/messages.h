// Engine structs to LCM messages (the only place that knows both).
#pragma once

#include <contactsim/contacts_t.hpp>
#include <contactsim/model_info_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/state_t.hpp>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"

namespace contactsim {

// A vector into a message's double[3] field.
inline void Copy3(const Vec3& v, double out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

state_t MakeStateMessage(const World& world);
contacts_t MakeContactsMessage(const World& world, const ContactSet& contacts, const ContactMethod& method);
// The world's models with their link and joint names and ids (MODEL_INFO).
model_info_t MakeModelInfoMessage(const World& world);
// reply_t codes equal StatusCode values by design.
reply_t MakeReply(const std::string& client_id, int64_t request_id, const Status& status, const World& world);

}  // namespace contactsim
