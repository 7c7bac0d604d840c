#include "service/server/server_config.h"

#include <contactsim/signature.h>

#include "service/collision/parallel_runner.h"
#include "service/physics/validation.h"
#include "service/scene/proto_text.h"
#include "service/server/command_decoder.h"

namespace contactsim {
namespace {

std::string Folder(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

Status LoadServerConfig(const std::string& path, proto::ServerConfig* config) {
  google::protobuf::TextFormat::ParseInfoTree tree;
  Status st = ReadTextProto(path, config, &tree);
  if (!st.ok()) return st;
  auto at = [&](const char* field) { return FieldLocation(path, &tree, *config, field) + ": "; };
  const struct {
    const char* name;
    double value, lo, hi;
  } ranges[] = {
      {"real_time_factor", config->real_time_factor(), 1e-3, 1e3},
      {"state_rate_hz", config->state_rate_hz(), 0.0, 1e6},
      {"contacts_rate_hz", config->contacts_rate_hz(), 0.0, 1e6},
      {"status_rate_hz", config->status_rate_hz(), 1e-3, 1e3},
  };
  for (const auto& r : ranges) {
    if (!(st = CheckInRange(r.name, r.value, r.lo, r.hi)).ok()) return Status::InvalidArgument(at(r.name) + st.message());
  }
  const struct {
    const char* name;
    int64_t value, lo;
  } counts[] = {
      {"max_bodies", config->max_bodies(), 1},
      {"max_joints", config->max_joints(), 0},
      {"max_convex_points", config->max_convex_points(), 4},
      {"max_body_cmd_bytes", config->max_body_cmd_bytes(), 256},
      {"max_scene_cmd_bytes", config->max_scene_cmd_bytes(), 256},
      {"max_joint_cmd_bytes", config->max_joint_cmd_bytes(), 256},
      {"max_input_bytes", config->max_input_bytes(), 256},
      {"max_queued_commands", config->max_queued_commands(), 1},
  };
  for (const auto& c : counts) {
    if (c.value < c.lo) {
      return Status::InvalidArgument(at(c.name) + c.name + " must be >= " + std::to_string(c.lo) + ", got " +
                                     std::to_string(c.value));
    }
  }
  if (!(st = CheckInRange("max_commands_per_second", config->max_commands_per_second(), 0.0, 1e9)).ok()) {
    return Status::InvalidArgument(at("max_commands_per_second") + st.message());
  }
  if (!(st = CheckInRange("command_burst", config->command_burst(), 1.0, 1e9)).ok()) {
    return Status::InvalidArgument(at("command_burst") + st.message());
  }
  if (!(st = CheckInRange("auth_window_s", config->auth_window_s(), 1e-3, 1e6)).ok()) {
    return Status::InvalidArgument(at("auth_window_s") + st.message());
  }
  static const char* kLevels[] = {"trace", "debug", "info", "warn", "error", "critical", "off"};
  bool level_ok = false;
  for (const char* l : kLevels) level_ok |= config->log_level() == l;
  if (!level_ok) {
    return Status::InvalidArgument(at("log_level") + "log_level must be one of trace, debug, info, warn, error, "
                                   "critical, off, got \"" + config->log_level() + "\"");
  }
  if (config->broadphase() != "sap" && config->broadphase() != "naive") {
    return Status::InvalidArgument(at("broadphase") + "broadphase must be sap or naive, got \"" +
                                   config->broadphase() + "\"");
  }
  if (config->has_threads() && !(st = CheckThreadCount(config->threads())).ok()) {
    return Status::InvalidArgument(at("threads") + st.message());
  }
  FsyncPolicy policy;
  if (!(st = ParseFsyncPolicy(config->journal_fsync(), &policy)).ok()) {
    return Status::InvalidArgument(at("journal_fsync") + st.message());
  }
  if (config->snapshot_every_steps() < 0 || config->max_snapshots() < 1) {
    return Status::InvalidArgument(at("snapshot_every_steps") + "snapshot_every_steps must be >= 0 and max_snapshots >= 1, got " +
                                   std::to_string(config->snapshot_every_steps()) + " and " +
                                   std::to_string(config->max_snapshots()));
  }
  LatePolicy late;
  if (!(st = ParseLatePolicy(config->late_policy(), &late)).ok()) return Status::InvalidArgument(at("late_policy") + st.message());
  if (!(st = CheckInRange("late_timeout_s", config->late_timeout_s(), 1e-4, 3600.0)).ok()) {
    return Status::InvalidArgument(at("late_timeout_s") + st.message());
  }
  ParamMap params;
  for (const auto& p : config->method_params()) params[p.name()] = p.value();
  std::shared_ptr<ContactMethod> method;
  if (!(st = MakeContactMethod(config->contact_method(), params, &method)).ok()) {
    return Status::InvalidArgument(at("contact_method") + st.message());
  }
  return Status::Ok();
}

Status MakeServerSetup(const proto::ServerConfig& config, const std::string& config_path,
                       const std::string& scene_override, ServerSetup* setup) {
  ServerSetup s;
  s.options.prefix = config.channel_prefix();
  s.options.mode = static_cast<RunMode>(config.mode());  // equal values by design
  s.options.real_time_factor = config.real_time_factor();
  s.options.start_paused = config.start_paused();
  s.options.state_rate_hz = config.state_rate_hz();
  s.options.contacts_rate_hz = config.contacts_rate_hz();
  s.options.status_rate_hz = config.status_rate_hz();
  s.options.broadphase = config.broadphase();
  s.options.threads = config.has_threads() ? config.threads() : DefaultThreadCount();  // checked by LoadServerConfig
  s.options.sleep = config.sleep();
  s.options.max_bodies = config.max_bodies();
  s.options.max_joints = config.max_joints();
  s.options.decode_limits = {config.max_convex_points(), config.max_body_cmd_bytes(), config.max_scene_cmd_bytes(),
                             config.max_joint_cmd_bytes(), config.max_input_bytes()};
  s.options.max_commands_per_second = config.max_commands_per_second();
  s.options.command_burst = config.command_burst();
  s.options.max_queued_commands = config.max_queued_commands();
  s.options.auth_window_s = config.auth_window_s();
  if (!config.auth_key_file().empty()) {
    const std::string path = config.auth_key_file()[0] == '/' ? config.auth_key_file()
                                                              : Folder(config_path) + "/" + config.auth_key_file();
    std::string error;
    if (!LoadAuthKey(path, &s.options.auth_key, &error)) {
      return Status::InvalidArgument(config_path + ": auth_key_file: " + error);
    }
  }
  s.options.live_line = config.live_line();
  if (!config.journal_dir().empty()) {
    s.options.journal_dir =
        config.journal_dir()[0] == '/' ? config.journal_dir() : Folder(config_path) + "/" + config.journal_dir();
  }
  ParseFsyncPolicy(config.journal_fsync(), &s.options.journal_fsync);  // checked by LoadServerConfig
  s.options.snapshot_every = config.snapshot_every_steps();
  ParseLatePolicy(config.late_policy(), &s.options.late_policy);  // checked by LoadServerConfig
  s.options.late_timeout = config.late_timeout_s();
  s.options.max_snapshots = config.max_snapshots();
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
