// The order and lines of a URDF's links and joints, and its tree, from the
// XML itself. urdfdom (urdf::parseURDF) keeps links and joints in maps
// sorted by name and reports errors without a line; reading the same text
// with tinyxml, which urdfdom parses with, recovers the file's order and
// each element's line, and lets the tree be checked (one root, one parent
// per link, no loop, known joint types) with messages that name the joint
// and its line before urdfdom sees the text.
#pragma once

#include <string>
#include <vector>

#include "service/model/model_description.h"
#include "service/model/read_limits.h"
#include "service/model/source_map.h"
#include "service/physics/status.h"

namespace contactsim::model {

struct UrdfStructure {
  std::string robot_name;
  std::vector<std::string> link_order;   // link names in the file's order
  std::vector<std::string> joint_order;  // joint names in the file's order
  std::string root_link;
};

// Parses `text` as XML (a malformed file fails with tinyxml's line and
// column), fills where's lines, checks the counts against `limits` and the
// tree (description_check.h's CheckTree).
Status ReadUrdfStructure(const std::string& text, const ReadLimits& limits, SourceMap* where, UrdfStructure* out);

// URDF's joint type attribute as an enum; false for any other word.
bool ParseUrdfJointType(const std::string& word, JointType* type);

}  // namespace contactsim::model
