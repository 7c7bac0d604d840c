// The checks of a model description that need no world: unique names,
// joints that name existing links, one tree with one root (no link is the
// child of two joints, no loop), finite poses, unit-able axes, masses and
// inertias a rigid body can have, limits in order, geometry sizes positive.
// A hand-made description passes through the same gate as a file's.
#pragma once

#include <string>
#include <vector>

#include "service/model/model_description.h"
#include "service/physics/status.h"

namespace contactsim::model {

// The tree of a checked description.
struct ModelTree {
  int root = -1;                     // index of the root link
  std::vector<int> parent_joint;     // per link: the joint whose child it is, -1 for the root
  std::vector<int> order;            // link indices, every parent before its children
};

// "model \"name\"" and ", link \"x\"" / ", joint \"y\"" prefixes for errors.
std::string ModelWhere(const ModelDescription& d);

Status CheckModel(const ModelDescription& d, ModelTree* tree);

// The inertia tensor a rigid body can have: symmetric, positive definite,
// and its principal moments obey the triangle inequality (each at most the
// sum of the other two), within round-off.
Status CheckInertia(const std::string& where, const Mat3& inertia);

}  // namespace contactsim::model
