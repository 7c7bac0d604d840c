// A URDF file into a ModelDescription, with urdfdom (urdf::parseURDF).
//
// Read: <robot name>; each <link> in the file's order with <inertial>
// (origin, mass, the six inertia entries), every <collision> and <visual>
// (origin; box, sphere, cylinder, mesh with scale; a visual's material
// colour, named at the robot level or inline); each <joint> in the file's
// order (revolute, continuous, prismatic, fixed, floating, planar; origin,
// axis normalised, <limit>, <dynamics damping friction>, <mimic joint
// multiplier offset>, checked by CheckMimics). An explicit mass of zero is
// a massless link (inertial left empty), as PyBullet reads it.
// Not read, and not refused: <transmission>, <gazebo>,
// <calibration>, <safety_controller>, textures, sensors; URDF has no
// capsule (urdfdom refuses one). docs/models.md lists them.
//
// Frames: a link's frame is its parent joint's frame; a joint's origin is
// its frame in the parent link's frame; the axis is in the joint (= child
// link) frame; inertia is about the centre of mass in the inertial origin's
// axes. Mesh URIs resolve with model_paths.h against the file's directory.
#pragma once

#include <string>

#include "service/model/model_description.h"
#include "service/model/model_paths.h"
#include "service/model/read_limits.h"
#include "service/physics/status.h"

namespace contactsim::model {

// source_path: the file the text came from (its directory resolves
// relative mesh paths; messages name it), or "<inline>".
Status ReadUrdf(const std::string& text, const std::string& source_path, const ModelPaths& paths,
                const ReadLimits& limits, ModelDescription* model);

}  // namespace contactsim::model
