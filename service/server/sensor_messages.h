// The messages of ray casts and sensors: a RAY_CAST's answer and the
// readings of the world's sensors after a step (lcmtypes/ray_hits_t.lcm,
// sensors_t.lcm).
#pragma once

#include <contactsim/ray_hits_t.hpp>
#include <contactsim/sensors_t.hpp>

#include <string>
#include <vector>

#include "service/collision/contact.h"
#include "service/collision/parallel_runner.h"
#include "service/collision/ray_cast.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"

namespace contactsim {

ray_hits_t MakeRayHitsMessage(const std::string& client_id, int64_t request_id, const World& world,
                              const std::vector<RayHit>& hits);

// Casts each range sensor's rays from its body's pose (its own body
// ignored) and sums each contact sensor's wrench from the step's contacts.
sensors_t MakeSensorsMessage(const World& world, const ContactSet& contacts, const ContactMethod& method,
                             ParallelRunner* runner);

}  // namespace contactsim
