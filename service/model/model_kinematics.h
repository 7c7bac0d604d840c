// Forward kinematics of a model description: the world pose of every link
// for given joint coordinates, by composing each joint's origin with its
// motion down the tree from the root,
//   X_W_child = X_W_parent * X_origin * X_motion(q),
// with X_motion a rotation by q about the axis (revolute, continuous), a
// translation q * axis (prismatic), the identity (fixed), a translation
// (x, y, z) then a rotation (qw, qx, qy, qz) (floating), or a translation
// x t1 + y t2 in the plane normal to the axis then a rotation theta about it
// (planar; t1, t2 from PerpendicularBasis(axis)). The axis is in the child
// frame, so the motion follows the origin (URDF's joint frame). The builder
// places bodies with it and the clients draw a model with it.
#pragma once

#include <vector>

#include "service/model/model_description.h"
#include "service/physics/status.h"

namespace contactsim::model {

// How many numbers a joint of this type takes: revolute, continuous and
// prismatic 1, fixed 0, planar 3 (x, y, theta), floating 7 (x, y, z, qw,
// qx, qy, qz).
int JointCoordinateCount(JointType type);

// Sum of JointCoordinateCount over the model's joints, in joint order.
int ModelCoordinateCount(const ModelDescription& model);

// World poses of model.links (same order) with the root link at `root`,
// for q the joints' coordinates concatenated in model.joints' order. The
// description must have passed the readers' checks (a tree with
// root_link set). InvalidArgument if q has the wrong size or is not finite.
Status LinkWorldPoses(const ModelDescription& model, const Pose& root, const std::vector<double>& q,
                      std::vector<Pose>* poses);

// a * b: b's frame given in a's, then a's in its parent's.
Pose Compose(const Pose& a, const Pose& b);

// The inverse: Compose(InversePose(a), a) is the identity.
Pose InversePose(const Pose& a);

}  // namespace contactsim::model
