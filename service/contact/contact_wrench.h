// The total contact wrench each of some bodies received in a step, summed
// from the step's contacts and the values the method wrote on them
// (contact_method.h, ContactValueKind): a contact pushes body B with
// normal_value n + tangent_value and body A with the opposite, at the
// contact point. Impulses over the step are divided by dt, so the wrench
// is the step's mean force and torque whatever the method, and a body at
// rest reads its weight: sum of contact forces + m g = m a (Newton).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"

namespace contactsim {

struct ContactWrench {
  Vec3 normal_force = Vec3::Zero();    // N, world: the normal parts
  Vec3 friction_force = Vec3::Zero();  // N, world: the tangential parts
  Vec3 torque = Vec3::Zero();          // N m, world, about the body's centre of mass
  int contacts = 0;                    // contacts that touched the body
};

// One wrench per id of `bodies`, in that order (zero for an absent body).
std::vector<ContactWrench> SumContactWrenches(const World& world, const std::vector<BodyId>& bodies,
                                              const ContactSet& contacts, ContactValueKind kind);

}  // namespace contactsim
