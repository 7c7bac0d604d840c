#include "service/server/server_config.h"

#include <contactsim/signature.h>
#include <glob.h>

#include "service/contact/contact_method_registry.h"
#include "service/physics/validation.h"
#include "service/scene/proto_text.h"
#include "service/server/arm_driver/arm_driver_config.h"
#include "service/server/arm_driver/wsg_driver_config.h"

namespace contactsim {
namespace {

std::string Folder(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

// A model_path entry with shell wildcards (glob(3)) stands for every folder
// it matches, in sorted order, so that a config can name a folder whose
// exact path differs between machines (a virtual environment's
// lib/python3*/site-packages); one that matches nothing is kept as written,
// for the error that lists the places tried.
void ExpandModelPath(const std::string& path, std::vector<std::string>* out) {
  glob_t matches{};
  if (path.find_first_of("*?[") != std::string::npos && glob(path.c_str(), GLOB_ONLYDIR, nullptr, &matches) == 0) {
    for (size_t i = 0; i < matches.gl_pathc; ++i) out->push_back(matches.gl_pathv[i]);
  } else {
    out->push_back(path);
  }
  globfree(&matches);
}

}  // namespace

Status LoadServerConfig(const std::string& path, proto::ServerConfig* config) {
  google::protobuf::TextFormat::ParseInfoTree tree;
  Status st = ReadTextProto(path, config, &tree);
  if (!st.ok()) return st;
  auto at = [&](const char* field) { return FieldLocation(path, &tree, *config, field) + ": "; };
  // the options' ranges and choices (server_options.h), checked on a scratch copy
  ServerOptions options;
  std::string field;
  if (!(st = ReadServerOptions(*config, &options, &field)).ok()) {
    return Status::InvalidArgument(at(field.c_str()) + st.message());
  }
  static const char* kLevels[] = {"trace", "debug", "info", "warn", "error", "critical", "off"};
  bool level_ok = false;
  for (const char* l : kLevels) level_ok |= config->log_level() == l;
  if (!level_ok) {
    return Status::InvalidArgument(at("log_level") + "log_level must be one of trace, debug, info, warn, error, "
                                   "critical, off, got \"" + config->log_level() + "\"");
  }
  ParamMap params;
  for (const auto& p : config->method_params()) params[p.name()] = p.value();
  std::shared_ptr<ContactMethod> method;
  if (!(st = MakeContactMethod(config->contact_method(), params, &method)).ok()) {
    return Status::InvalidArgument(at("contact_method") + st.message());
  }
  ArmDriverConfig arm;
  if (config->has_arm_driver() &&
      !(st = ReadArmDriverConfig(config->arm_driver(), options.prefix, &arm, &field)).ok()) {
    const auto* block = tree.GetTreeForNested(config->GetDescriptor()->FindFieldByName("arm_driver"), -1);
    return Status::InvalidArgument(FieldLocation(path, block, config->arm_driver(), field) + ": arm_driver: " +
                                   st.message());
  }
  WsgDriverConfig wsg;
  if (config->has_wsg_driver()) {
    const auto* block = tree.GetTreeForNested(config->GetDescriptor()->FindFieldByName("wsg_driver"), -1);
    st = ReadWsgDriverConfig(config->wsg_driver(), options.prefix, &wsg, &field);
    // one channel serves one driver
    if (st.ok() && config->has_arm_driver()) {
      for (const std::string* c : {&wsg.command_channel, &wsg.status_channel}) {
        if (*c == arm.command_channel || *c == arm.status_channel) {
          field = c == &wsg.command_channel ? "command_channel" : "status_channel";
          st = Status::InvalidArgument(field + " \"" + *c + "\" is also one of arm_driver's channels");
          break;
        }
      }
    }
    if (!st.ok()) {
      return Status::InvalidArgument(FieldLocation(path, block, config->wsg_driver(), field) + ": wsg_driver: " +
                                     st.message());
    }
  }
  return Status::Ok();
}

Status MakeServerSetup(const proto::ServerConfig& config, const std::string& config_path,
                       const std::string& scene_override, ServerSetup* setup) {
  ServerSetup s;
  ReadServerOptions(config, &s.options);  // checked by LoadServerConfig
  if (config.has_arm_driver()) {
    ArmDriverConfig arm;
    std::string field;
    Status st = ReadArmDriverConfig(config.arm_driver(), s.options.prefix, &arm, &field);
    if (!st.ok()) return st.Prefixed(config_path + ": arm_driver: ");
    s.options.arm_driver = std::move(arm);
  }
  if (config.has_wsg_driver()) {
    WsgDriverConfig wsg;
    std::string field;
    Status st = ReadWsgDriverConfig(config.wsg_driver(), s.options.prefix, &wsg, &field);
    if (!st.ok()) return st.Prefixed(config_path + ": wsg_driver: ");
    s.options.wsg_driver = std::move(wsg);
  }
  if (!config.auth_key_file().empty()) {
    const std::string path = config.auth_key_file()[0] == '/' ? config.auth_key_file()
                                                              : Folder(config_path) + "/" + config.auth_key_file();
    std::string error;
    if (!LoadAuthKey(path, &s.options.auth_key, &error)) {
      return Status::InvalidArgument(config_path + ": auth_key_file: " + error);
    }
  }
  if (!config.journal_dir().empty()) {
    s.options.journal_dir =
        config.journal_dir()[0] == '/' ? config.journal_dir() : Folder(config_path) + "/" + config.journal_dir();
  }
  for (const std::string& p : config.model_path()) {
    ExpandModelPath(!p.empty() && p[0] == '/' ? p : Folder(config_path) + "/" + p, &s.options.model_paths);
  }
  s.lcm_url = config.lcm_url();
  s.log_level = config.log_level();

  ParamMap params;
  for (const auto& p : config.method_params()) params[p.name()] = p.value();
  Status st = MakeContactMethod(config.contact_method(), params, &s.method);
  if (!st.ok()) return Status::InvalidArgument(config_path + ": contact_method: " + st.message());

  if (!scene_override.empty()) {
    s.scene_path = scene_override;
  } else if (config.has_scene() && !config.scene().empty()) {
    s.scene_path = config.scene()[0] == '/' ? config.scene() : Folder(config_path) + "/" + config.scene();
  }
  if (!s.scene_path.empty()) {
    s.scene = std::make_shared<SceneSpec>();
    if (!(st = LoadSceneFile(s.scene_path, s.scene.get())).ok()) return st;
    if (!s.scene->contact_method.empty() &&
        !(st = MakeContactMethod(s.scene->contact_method, s.scene->method_params, &s.method)).ok()) {
      return Status::InvalidArgument(s.scene_path + ": contact_method: " + st.message());
    }
  }
  *setup = std::move(s);
  return Status::Ok();
}

}  // namespace contactsim
