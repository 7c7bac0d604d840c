// JOINT_STATE: every joint with a coordinate, grouped by model (docs/actuators.md,
// "Joint channels").
#pragma once

#include <contactsim/joint_state_t.hpp>

#include "service/physics/world.h"

namespace contactsim {

// The joints with a coordinate (hinge, prismatic): each model's in its
// order (ModelCoordinateJoints), the models in load order, then the joints
// of no model by ascending id, named by their id in decimal.
joint_state_t MakeJointStateMessage(const World& world);

}  // namespace contactsim
