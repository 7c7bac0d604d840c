// Robot models listed in a scene file (scene.proto's `models`): read when
// the scene is read, so a bad file is an error of the scene's with its
// line, and added by BuildWorld after the scene's bodies and joints, each as
// a whole (model_adder.h). A model's path is looked for in the scene file's
// folder, then along the environment's model paths (model_paths.h).
#pragma once

#include <google/protobuf/text_format.h>

#include <memory>
#include <string>
#include <vector>

#include "service/model/model_builder.h"
#include "service/model/model_paths.h"
#include "service/physics/status.h"
#include "service/physics/world.h"
#include "service/proto/scene.pb.h"

namespace contactsim {

struct SceneModel {
  std::shared_ptr<const model::ModelDescription> description;
  model::ModelOptions options;
  std::string origin;  // "FILE:LINE: models[i]", for errors
};

// Reads one model entry, its file looked for along `paths`; errors start
// with `origin`.
Status ReadSceneModel(const proto::SceneModel& entry, const model::ModelPaths& paths, const std::string& origin,
                      SceneModel* out);

// Reads every model the scene lists.
Status ReadSceneModels(const proto::Scene& scene, const std::string& filename,
                       const google::protobuf::TextFormat::ParseInfoTree* tree, std::vector<SceneModel>* models);

// Builds and adds them to *world in order; on error *world may hold some
// of them (BuildWorld builds into a world of its own and drops it).
Status AddSceneModels(const std::vector<SceneModel>& models, const Material& default_material, World* world);

}  // namespace contactsim
