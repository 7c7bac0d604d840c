// An SDF model with its nested models as one list of links and one of
// joints, with scoped names ("outer::inner::link") and every link and joint
// frame resolved (sdf::SemanticPose) into the top model's frame. The SDF
// reader (sdf_reader.h) turns the lists into a description.
#pragma once

#include <sdf/Joint.hh>
#include <sdf/Link.hh>
#include <sdf/Model.hh>

#include <string>
#include <vector>

#include "service/model/model_description.h"
#include "service/physics/status.h"

namespace contactsim::model {

struct FlatSdfLink {
  std::string name;               // scoped
  const sdf::Link* link = nullptr;
  Pose pose;                      // link frame in the top model frame
  int line = 0;                   // 0: unknown
};

struct FlatSdfJoint {
  std::string name;               // scoped
  std::string parent, child;      // scoped link names; "world" for the world
  const sdf::Joint* joint = nullptr;
  Pose pose;                      // joint frame in the top model frame
  int line = 0;
};

struct FlatSdfModel {
  std::vector<FlatSdfLink> links;    // depth first, in the file's order
  std::vector<FlatSdfJoint> joints;
};

// Appends `model`'s links and joints, then its nested models', under
// `prefix` ("" for the top model), with `pose` the model frame in the top
// model frame (identity for the top model).
Status FlattenSdfModel(const sdf::Model& model, const std::string& prefix, const Pose& pose, FlatSdfModel* out);

// ignition's pose as ours.
Pose FromIgnition(const ignition::math::Pose3d& p);

// The first error's message with its line, "" when there is none.
std::string FirstError(const sdf::Errors& errors);

}  // namespace contactsim::model
