// The joints' coordinates on the wire: JOINT_STATE, and the joint block of
// STATE (docs/actuators.md, "Joint channels"). One walk over the joints
// writes both, so the two list the same joints in the same order.
#pragma once

#include <contactsim/joint_state_t.hpp>
#include <contactsim/state_t.hpp>

#include "service/physics/world.h"

namespace contactsim {

// The joints with a coordinate (hinge, prismatic): each model's in its
// order (ModelCoordinateJoints), the models in load order, then the joints
// of no model by ascending id, named by their id in decimal.
joint_state_t MakeJointStateMessage(const World& world);

// The same joints, without names, into STATE's joint block (empty when the
// world has none).
void FillStateJoints(const World& world, state_t* msg);

// True while the world has a joint with a coordinate (JOINT_STATE is then
// published with STATE).
bool HasCoordinateJoints(const World& world);

}  // namespace contactsim
