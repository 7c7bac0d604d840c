// A model description, and link poses from its forward kinematics, as JSON
// for contactsim-model-info: every number with 17 significant digits, so
// that a reader gets the double the description holds.
#pragma once

#include <string>
#include <vector>

#include "service/model/model_description.h"

namespace contactsim::tools {

std::string DescriptionJson(const model::ModelDescription& model);

// One array per configuration of {"link": ..., "position": [...],
// "orientation": [w, x, y, z]} in the description's link order.
std::string PosesJson(const model::ModelDescription& model, const std::vector<std::vector<model::Pose>>& poses);

}  // namespace contactsim::tools
