// Adds a built model (model_builder.h) to a world as a whole, and removes
// it as a whole. Adding is two steps so that the caller can put its own
// checks (limits, the contact method's contract) between them: Prepare
// creates every body and joint against the world without changing it, and
// Commit adds them and the model's record. A prepared model that is
// committed at once always fits: the ids it was prepared with are the ones
// the world hands out next.
#pragma once

#include <vector>

#include "service/model/model_builder.h"
#include "service/physics/world.h"

namespace contactsim::model {

struct PreparedModel {
  std::vector<RigidBody> bodies;       // with the ids the world will give them
  std::vector<JointSettings> joints;   // with those body ids
  ModelBuild build;
};

// Creates every body and joint (the engine's own gates, CreateBody and
// CreateJoint) and checks that the model's name is free. Changes nothing.
Status PrepareModel(ModelBuild build, const World& world, const Material& default_material, PreparedModel* out);

// Adds the prepared bodies, joints and record; *record is the world's copy.
Status CommitModel(PreparedModel prepared, World* world, ModelRecord* record);

// Removes the model's bodies (and with them its joints) and its record.
Status RemoveModel(ModelId id, World* world, ModelRecord* removed);

// The model with this id, or null.
const ModelRecord* FindModel(const World& world, ModelId id);
// The model that holds this body, or null.
const ModelRecord* ModelOfBody(const World& world, BodyId body);

}  // namespace contactsim::model
