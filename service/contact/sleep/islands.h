// Islands of awake dynamic bodies (Box2D's islands; Catto, "Box2D v3
// islands", and Bullet's btSimulationIslandManager): two bodies share an
// island when a contact of the last step, a joint, or a pair of overlapping
// wake boxes (island_sleep.h) joins them. Static and kinematic bodies join
// no island: they do not connect their neighbours, so two stacks on one
// ground are two islands. Sleeping bodies are not stepped and join none.
#pragma once

#include <vector>

#include "service/collision/broadphase.h"
#include "service/collision/contact.h"
#include "service/physics/world.h"

namespace contactsim {

// For every body index, the index of its island's first (lowest id) body,
// or -1 for a body in no island (static, kinematic or asleep). `near` are
// extra pairs of body indices to join (the wake boxes that overlapped).
std::vector<int> FindIslands(const World& world, const ContactSet& contacts, const std::vector<BodyPair>& near);

}  // namespace contactsim
