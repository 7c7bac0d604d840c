#include "service/scene/scene_models.h"

#include "service/model/model_adder.h"
#include "service/model/model_file.h"
#include "service/model/model_paths.h"
#include "service/physics/hull_vertex_budget.h"
#include "service/physics/validation.h"
#include "service/scene/proto_text.h"

namespace contactsim {

Status ReadSceneModel(const proto::SceneModel& m, const model::ModelPaths& paths, const std::string& origin,
                      SceneModel* model_out) {
  SceneModel out;
  out.origin = origin;
  auto d = std::make_shared<model::ModelDescription>();
  Status st = model::ReadModelFile(m.path(), paths, model::ReadLimits(), d.get());
  if (!st.ok()) return st.Prefixed(out.origin + ": ");
  out.description = std::move(d);
  out.options.name = m.name();
  out.options.base.position = Vec3(m.position().x(), m.position().y(), m.position().z());
  Quat q;
  const Eigen::Vector4d wxyz(m.orientation().w(), m.orientation().x(), m.orientation().y(), m.orientation().z());
  if (!(st = CheckFinite("position", out.options.base.position)).ok() ||
      !(st = MakeOrientation("orientation", wxyz, true, &q)).ok()) {
    return st.Prefixed(out.origin + ": ");
  }
  out.options.base.orientation = q;
  out.options.fixed_base = m.fixed_base();
  out.options.self_collide = m.self_collide();
  if (!(st = ResolveMaxHullVertices(m.max_hull_vertices(), &out.options.max_hull_vertices)).ok()) {
    return st.Prefixed(out.origin + ": ");
  }
  *model_out = std::move(out);
  return Status::Ok();
}

Status ReadSceneModels(const proto::Scene& p, const std::string& filename,
                       const google::protobuf::TextFormat::ParseInfoTree* tree, std::vector<SceneModel>* models) {
  const model::ModelPaths paths =
      model::MakeModelPaths({}, {model::DirectoryOf(filename)}, model::ModelPathEnvironment());
  for (int i = 0; i < p.models_size(); ++i) {
    SceneModel out;
    const std::string origin = FieldLocation(filename, tree, p, "models", i) + ": models[" + std::to_string(i) + "]";
    const Status st = ReadSceneModel(p.models(i), paths, origin, &out);
    if (!st.ok()) return st;
    models->push_back(std::move(out));
  }
  return Status::Ok();
}

Status AddSceneModels(const std::vector<SceneModel>& models, const Material& default_material, World* world) {
  for (const SceneModel& m : models) {
    model::ModelBuild build;
    model::PreparedModel prepared;
    ModelRecord record;
    Status st = model::BuildModel(*m.description, m.options, &build);
    if (st.ok()) st = model::PrepareModel(std::move(build), *world, default_material, &prepared);
    if (st.ok()) st = model::CommitModel(std::move(prepared), world, &record);
    if (!st.ok()) return st.Prefixed(m.origin + ": ");
  }
  return Status::Ok();
}

}  // namespace contactsim
