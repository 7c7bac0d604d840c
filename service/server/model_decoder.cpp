// MODEL_CMD's decoder: the checks that need no world, and for a LOAD the
// reading of the model (its file or inline text, and its meshes) on the LCM
// thread. The command is then kept in its resolved form, the model as read
// serialized into the message (model_cmd_t FORMAT_RESOLVED), which is what
// the journal records: a replay or a recovery builds the model from those
// bytes, not from files that may have changed or gone since.
#include <contactsim/model_cmd_t.hpp>

#include "service/model/model_file.h"
#include "service/physics/hull_vertex_budget.h"
#include "service/physics/validation.h"
#include "service/proto/model.pb.h"
#include "service/scene/model_proto.h"
#include "service/server/command_decoder.h"

namespace contactsim {
namespace {

constexpr size_t kMaxModelName = 256;   // bytes
constexpr size_t kMaxModelPath = 4096;  // bytes, as PATH_MAX

// A format the client named must be the one the text's top element shows
// (a file's is checked by its reader, which reads the same element).
Status CheckFormat(const model_cmd_t& m) {
  if (m.format == model_cmd_t::FORMAT_AUTO || m.text.empty()) return Status::Ok();
  model::ModelFormat found;
  Status st = model::DetectModelFormat(m.text, "<inline>", &found);
  if (!st.ok()) return st;
  const bool urdf = found == model::ModelFormat::kUrdf;
  if (urdf != (m.format == model_cmd_t::FORMAT_URDF)) {
    return Status::InvalidArgument(std::string("format says ") + (urdf ? "SDF" : "URDF") + ", but the text is " +
                                   (urdf ? "URDF (<robot>)" : "SDF (<sdf>)"));
  }
  return Status::Ok();
}

// The model a LOAD names: from its resolved bytes, or read from its path or
// text; on success *resolved holds the bytes the journal keeps.
Status ReadLoadedModel(const model_cmd_t& m, const DecodeContext& context, model::ModelDescription* d,
                       std::string* resolved) {
  if (m.format == model_cmd_t::FORMAT_RESOLVED) {
    proto::ModelDescription p;
    if (m.resolved.empty() || !p.ParseFromArray(m.resolved.data(), static_cast<int>(m.resolved.size()))) {
      return Status::InvalidArgument("resolved: not a serialized model description (" +
                                     std::to_string(m.resolved.size()) + " bytes)");
    }
    resolved->clear();  // the payload as it came is the resolved form already
    return LoadModelDescription(p, d);
  }
  if (m.format < model_cmd_t::FORMAT_AUTO || m.format > model_cmd_t::FORMAT_SDF) {
    return Status::InvalidArgument("format must be AUTO, URDF, SDF or RESOLVED (0-3), got " + std::to_string(m.format));
  }
  if (m.path.empty() == m.text.empty()) {
    return Status::InvalidArgument("a LOAD gives a path or the text of a model file, exactly one of them");
  }
  if (m.path.size() > kMaxModelPath) {
    return Status::InvalidArgument("path of " + std::to_string(m.path.size()) + " bytes is longer than 4096");
  }
  if (m.text.size() > static_cast<size_t>(context.limits.max_model_text_bytes)) {
    return Status::ResourceExhausted("text of " + std::to_string(m.text.size()) +
                                     " bytes exceeds max_model_text_bytes = " +
                                     std::to_string(context.limits.max_model_text_bytes));
  }
  Status st = CheckFormat(m);
  if (st.ok()) {
    st = m.path.empty() ? model::ReadModelText(m.text, "<inline>", context.model_paths, model::ReadLimits(), d)
                        : model::ReadModelFile(m.path, context.model_paths, model::ReadLimits(), d);
  }
  if (!st.ok()) return st;
  proto::ModelDescription p;
  SaveModelDescription(*d, &p);
  model_cmd_t kept = m;
  kept.format = model_cmd_t::FORMAT_RESOLVED;
  kept.path.clear();
  kept.text.clear();
  const std::string bytes = p.SerializeAsString();
  kept.resolved.assign(bytes.begin(), bytes.end());
  kept.resolved_size = static_cast<int32_t>(kept.resolved.size());
  resolved->resize(kept.getEncodedSize());
  kept.encode(resolved->data(), 0, static_cast<int>(resolved->size()));
  return Status::Ok();
}

Status DecodeLoad(const model_cmd_t& m, const DecodeContext& context, Command* cmd) {
  if (m.name.size() > kMaxModelName) {
    return Status::InvalidArgument("name of " + std::to_string(m.name.size()) + " bytes is longer than 256");
  }
  model::ModelOptions& o = cmd->model_options;
  o.name = m.name;
  o.base.position = Vec3(m.position[0], m.position[1], m.position[2]);
  Status st = CheckFinite("position", o.base.position);
  if (st.ok()) {
    st = MakeOrientation("orientation",
                         Eigen::Vector4d(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]),
                         true, &o.base.orientation);
  }
  if (!st.ok()) return st;
  o.fixed_base = m.fixed_base;
  o.self_collide = m.self_collide;
  if (!(st = ResolveMaxHullVertices(m.max_hull_vertices, &o.max_hull_vertices)).ok()) return st;
  auto d = std::make_shared<model::ModelDescription>();
  std::string resolved;
  if (!(st = ReadLoadedModel(m, context, d.get(), &resolved)).ok()) return st;
  cmd->kind = Command::Kind::kLoadModel;
  cmd->model = std::move(d);
  cmd->model_material = context.default_material;
  cmd->payload = std::move(resolved);  // empty: the payload as it came
  return Status::Ok();
}

}  // namespace

Status DecodeModelCommand(const model_cmd_t& m, const DecodeContext& context, Command* cmd) {
  cmd->record = RecordKind::kModelCommand;
  switch (m.op) {
    case model_cmd_t::LOAD:
      return DecodeLoad(m, context, cmd);
    case model_cmd_t::REMOVE:
      cmd->kind = Command::Kind::kRemoveModel;
      cmd->model_id = m.model_id;
      return Status::Ok();
    case model_cmd_t::INFO:
      cmd->kind = Command::Kind::kModelInfo;
      return Status::Ok();
    default:
      return Status::InvalidArgument("op must be LOAD, REMOVE or INFO (1-3), got " + std::to_string(m.op));
  }
}

}  // namespace contactsim
