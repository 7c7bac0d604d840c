// Robot model half of contactsim::Client: model_cmd_t on <prefix>_MODEL_CMD
// and the model list on <prefix>_MODEL_INFO (docs/models.md). As for bodies,
// the server is the one gate for bad input; nothing is checked here.
#include <algorithm>

#include "contactsim/client.h"
#include "contactsim/protocol.hpp"

namespace contactsim {
namespace {

int64_t Lookup(const std::vector<std::string>& names, const std::vector<int64_t>& ids, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : ids[it - names.begin()];
}

}  // namespace

int64_t Model::BodyId(const std::string& link) const { return Lookup(links, link_bodies, link); }
int64_t Model::JointId(const std::string& joint) const { return Lookup(joints, joint_ids, joint); }

Model Model::FromInfo(const model_entry_t& e) {
  Model m;
  m.id = e.model_id;
  m.name = e.name;
  m.links = e.link_names;
  m.link_bodies = e.link_bodies;
  m.joints = e.joint_names;
  m.joint_ids = e.joint_ids;
  return m;
}

std::optional<model_info_t> Client::WaitForModelInfo(uint64_t after,
                                                     const std::function<bool(const model_info_t&)>& predicate) {
  std::unique_lock<std::mutex> lock(mutex_);
  const bool got = changed_.wait_for(lock, options_.reply_timeout, [&] {
    return model_infos_received_ > after && latest_model_info_ && predicate(*latest_model_info_);
  });
  if (!got) return std::nullopt;
  return latest_model_info_;
}

Result<Model> Client::LoadModel(const std::string& path_or_text, const ModelOptions& options) {
  model_cmd_t command{};  // lcm-gen types leave numbers uninitialised
  command.op = model_cmd_t::LOAD;
  command.format = options.format;
  const size_t first = path_or_text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && path_or_text[first] == '<') {
    command.text = path_or_text;
  } else {
    command.path = path_or_text;
  }
  command.name = options.name;
  std::copy(options.position.data(), options.position.data() + 3, command.position);
  std::copy(options.orientation.begin(), options.orientation.end(), command.orientation);
  command.fixed_base = options.fixed_base;
  command.self_collide = options.self_collide;
  command.max_hull_vertices = options.max_hull_vertices;
  Result<Model> out;
  out.status = Send(command);
  if (!out.ok()) return out;
  if (out.status.ids.empty()) {
    out.status.code = ReplyCode::kInternal;
    out.status.message = "LOAD reply without a model id";
    return out;
  }
  const int64_t id = out.status.ids[0];
  auto has = [id](const model_info_t& info) {
    return std::any_of(info.models.begin(), info.models.end(), [id](const model_entry_t& e) { return e.model_id == id; });
  };
  std::optional<model_info_t> info;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (latest_model_info_ && has(*latest_model_info_)) info = latest_model_info_;
  }
  if (!info) {
    Result<std::vector<Model>> all = Models();
    if (!all.ok()) {
      out.status = all.status;
      return out;
    }
    for (const Model& m : all.value) {
      if (m.id == id) out.value = m;
    }
    return out;
  }
  for (const model_entry_t& e : info->models) {
    if (e.model_id == id) out.value = Model::FromInfo(e);
  }
  return out;
}

CommandResult Client::RemoveModel(int64_t id) {
  model_cmd_t command{};
  command.op = model_cmd_t::REMOVE;
  command.model_id = id;
  return Send(command);
}

Result<std::vector<Model>> Client::Models() {
  uint64_t seen;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    seen = model_infos_received_;
  }
  model_cmd_t command{};
  command.op = model_cmd_t::INFO;
  Result<std::vector<Model>> out;
  out.status = Send(command);
  if (!out.ok()) return out;
  const std::optional<model_info_t> info = WaitForModelInfo(seen, [](const model_info_t&) { return true; });
  if (!info) {
    out.status.code = ReplyCode::kTimeout;
    out.status.message = "no MODEL_INFO after INFO";
    return out;
  }
  for (const model_entry_t& e : info->models) out.value.push_back(Model::FromInfo(e));
  return out;
}

CommandResult Client::Send(model_cmd_t command) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  command.resolved_size = static_cast<int32_t>(command.resolved.size());
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kModelCmd), command.request_id, buffer.data(), static_cast<int>(buffer.size()));
}

}  // namespace contactsim
