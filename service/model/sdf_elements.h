// The parts of an SDF model as description parts: geometry, a link's
// inertial, collision and visual elements re-expressed in the link's
// description frame, and a joint's type, axis, limits and dynamics. The SDF
// reader (sdf_reader.h) says which frames and which types.
#pragma once

#include <sdf/Geometry.hh>
#include <sdf/Joint.hh>

#include <string>

#include "service/model/model_description.h"
#include "service/model/sdf_flatten.h"
#include "service/model/source_map.h"
#include "service/physics/status.h"

namespace contactsim::model {

// Box, sphere, cylinder, capsule and mesh (its file name as written, or
// made relative to the file it came from); any other type is refused,
// `where` starting the message.
Status SdfGeometry(const sdf::Geometry& in, const std::string& where, Geometry* out);

// The link's inertial (none for a zero mass), collisions and visuals, with
// their poses in `frame`, the link's description frame given in the top
// model frame.
Status SdfLinkElements(const FlatSdfLink& flat, const Pose& frame, const SourceMap& where, Link* out);

// Type, axis (in the joint frame), limits and dynamics of a revolute,
// continuous, prismatic or fixed joint; other types are refused.
Status SdfJointMotion(const sdf::Joint& in, const std::string& where, ModelJoint* out);

}  // namespace contactsim::model
