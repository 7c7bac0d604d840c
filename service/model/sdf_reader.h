// An SDF file into a ModelDescription, with libsdformat
// (sdf::Root::LoadSdfString, which also converts SDF 1.4-1.8 files to its
// own version and checks the frame graph).
//
// The model: the file's top <model>, or the one <model> of its <world> (a
// world with several is refused with their names). Nested models are
// flattened: their links and joints take scoped names "outer::inner::link",
// in depth-first file order (a model's own links, then its nested models').
//
// Frames: SDF poses are resolved with sdformat's SemanticPose into the frames
// the description uses. A non-root link's description frame is its parent
// joint's frame (as in URDF, so that the joint moves about the frame's
// origin); the root link's is its SDF link frame. Inertial, collision and
// visual poses are re-expressed in that frame, and a joint's axis is
// resolved in the joint frame (its <xyz expressed_in> honoured). When a
// joint sits at its child link's origin (the usual case) the two frames are
// the same.
//
// Joints: revolute (a revolute with SDF's default, unbounded limits becomes
// continuous), continuous, prismatic, fixed; ball, universal, revolute2,
// screw and gearbox are refused, as is a joint to the world (load the model
// with a fixed base instead). Geometry: box, sphere, cylinder, capsule,
// mesh; plane, ellipsoid, heightmap and polyline are refused. <self_collide>
// is read; <static>, plugins, sensors, lights, surface parameters and
// <frame>s beyond pose resolution are not (docs/models.md lists them).
#pragma once

#include <string>

#include "service/model/model_description.h"
#include "service/model/model_paths.h"
#include "service/model/read_limits.h"
#include "service/physics/status.h"

namespace contactsim::model {

// source_path: the file the text came from (its directory resolves
// relative mesh paths and <include>s; messages name it), or "<inline>".
Status ReadSdf(const std::string& text, const std::string& source_path, const ModelPaths& paths,
               const ReadLimits& limits, ModelDescription* model);

}  // namespace contactsim::model
