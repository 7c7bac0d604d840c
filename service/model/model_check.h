// The builder's gate on a description: the readers' own checks
// (description_check.h: names, one tree, finite values, masses and
// inertias a body can have), run again because a description also arrives
// hand-made or from a journal, and the tree's order for the builder.
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
  std::vector<int> parent_link;      // per link: its parent link, -1 for the root
  std::vector<int> order;            // link indices, every parent before its children
};

// "model \"name\" (source)" for the builder's errors.
std::string ModelWhere(const ModelDescription& d);

// Checks *d (setting its root link and normalising its axes, as the readers
// do) and orders its tree. Errors start with ModelWhere.
Status CheckModel(ModelDescription* d, ModelTree* tree);

}  // namespace contactsim::model
