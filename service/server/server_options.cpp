#include "service/server/server_options.h"

#include <climits>

#include "service/contact/param_docs.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

using SO = ServerOptions;
using DL = DecodeLimits;
constexpr double kNoMax = INT64_MAX;

const std::vector<const char*> kFsyncChoices = {"always", "none"};  // FsyncPolicy's order
const std::vector<const char*> kLateChoices = {"wait", "reuse", "drop"};

}  // namespace

const std::vector<ServerOption>& ServerOptionTable() {
  static const std::vector<ServerOption> table = {
      {"channel_prefix", &SO::prefix, 0, 0, {}, "", "channels are `<prefix>_BODY_CMD`, `<prefix>_STATE`, ..."},
      {"mode", &SO::mode, 0, 0, {"REALTIME", "FREE_RUN", "LOCKSTEP"}, "",
       "paced to the wall clock times real_time_factor; as fast as the machine allows; each step waits for every "
       "registered controller's input (docs/lockstep.md)"},
      {"real_time_factor", &SO::real_time_factor, 1e-3, 1e3, {}, "sim s / wall s", "pace of REALTIME"},
      {"start_paused", &SO::start_paused, 0, 0, {}, "", "start paused (STEP and RESUME run it)"},
      {"state_rate_hz", &SO::state_rate_hz, 0, 1e6, {}, "Hz of simulated time", "STATE rate; 0 = every step"},
      {"contacts_rate_hz", &SO::contacts_rate_hz, 0, 1e6, {}, "Hz of simulated time", "CONTACTS rate; 0 = every step"},
      {"status_rate_hz", &SO::status_rate_hz, 1e-3, 1e3, {}, "Hz of wall-clock time", "STATUS rate"},
      {"broadphase", &SO::broadphase, 0, 0, {"sap", "naive"}, "", "sweep and prune, or every pair"},
      {"threads", &SO::threads, 1, kMaxThreads, {}, "",
       "threads of the collision detector and of soft's and xpbd's solvers, in the world's oneTBB arena "
       "(docs/architecture.md, \"Threads\"); 1 is the serial code path; any count gives the same state bit for bit",
       "the machine's hardware threads"},
      {"sleep", &SO::sleep, 0, 0, {}, "",
       "settled islands sleep until something wakes them (docs/physics.md, \"Sleeping\"), as in Box2D, Bullet and "
       "Jolt"},
      {"manifold_reuse", &SO::manifold_reuse, 0, 0, {}, "",
       "a touching pair of boxes or hulls keeps its contact points while the two moved less than a tenth of the "
       "method's margin relative to each other, and recomputes their depths from the poses instead of colliding "
       "again (docs/physics.md, \"Manifold reuse\"); snapshots carry the kept points, so a restored run continues "
       "bit for bit; false collides every pair afresh"},
      {"live_line", &SO::live_line, 0, 0, {}, "", "a one-line progress report on stderr"},
      {"joint_state", &SO::joint_state, 0, 0, JointStateChoices(), "",
       "when JOINT_STATE is published with STATE, whose joint block carries the same joints: always; "
       "outside_lockstep (not while lockstep controllers are registered: they read STATE, one datagram a step); "
       "off (docs/actuators.md, \"Joint channels\")"},
      {"max_bodies", &SO::max_bodies, 1, INT_MAX, {}, "bodies", "ADD beyond this is refused"},
      {"max_joints", &SO::max_joints, 0, INT_MAX, {}, "joints", "joint ADD beyond this is refused"},
      {"max_convex_points", &DL::max_convex_points, 4, INT_MAX, {}, "points", "points of one CONVEX body"},
      {"max_body_cmd_bytes", &DL::max_body_cmd_bytes, 256, INT_MAX, {}, "bytes", "payload of one BODY_CMD"},
      {"max_scene_cmd_bytes", &DL::max_scene_cmd_bytes, 256, INT_MAX, {}, "bytes", "payload of one SCENE_CMD"},
      {"max_joint_cmd_bytes", &DL::max_joint_cmd_bytes, 256, INT_MAX, {}, "bytes", "payload of one JOINT_CMD"},
      {"max_model_cmd_bytes", &DL::max_model_cmd_bytes, 1024, INT_MAX, {}, "bytes",
       "payload of one MODEL_CMD (a model as the journal keeps it carries its mesh vertices)"},
      {"max_model_text_bytes", &DL::max_model_text_bytes, 1024, INT_MAX, {}, "bytes",
       "inline text of one model file in a MODEL_CMD LOAD"},
      {"max_input_bytes", &DL::max_input_bytes, 256, INT_MAX, {}, "bytes", "payload of one INPUT"},
      {"max_rays_per_cast", &DL::max_rays_per_cast, 1, INT_MAX, {}, "rays", "rays of one RAY_CAST"},
      {"max_rays_per_sensor", &DL::max_rays_per_sensor, 1, INT_MAX, {}, "rays", "rays of one range sensor"},
      {"max_ray_cast_bytes", &DL::max_ray_cast_bytes, 256, INT_MAX, {}, "bytes", "payload of one RAY_CAST"},
      {"max_sensor_cmd_bytes", &DL::max_sensor_cmd_bytes, 256, INT_MAX, {}, "bytes", "payload of one SENSOR_CMD"},
      {"max_commands_per_second", &SO::max_commands_per_second, 0, 1e9, {}, "1/s",
       "per client id, a token bucket (lockstep inputs not counted); 0 = no limit"},
      {"command_burst", &SO::command_burst, 1, 1e9, {}, "commands", "commands a client may send at once"},
      {"max_queued_commands", &SO::max_queued_commands, 1, INT_MAX, {}, "commands",
       "waiting for the next step, all clients together"},
      {"auth_window_s", &SO::auth_window_s, 1e-3, 1e6, {}, "s", "a signed command older or newer than this is stale"},
      {"journal_fsync", &SO::journal_fsync, 0, 0, kFsyncChoices, "",
       "always: each batch is fsynced before it is acknowledged; none: written before, synced by the kernel "
       "(survives a killed server, not a power loss)"},
      {"snapshot_every_steps", &SO::snapshot_every, 0, kNoMax, {}, "steps",
       "periodic snapshots for REWIND and recovery (docs/snapshots.md); 0 = none"},
      {"max_snapshots", &SO::max_snapshots, 1, INT_MAX, {}, "snapshots",
       "periodic ones kept in memory for REWIND; older history is dropped"},
      {"late_policy", &SO::late_policy, 0, 0, kLateChoices, "",
       "for lockstep controllers registered without one (docs/lockstep.md)"},
      {"late_timeout_s", &SO::late_timeout, 1e-4, 3600, {}, "s of wall-clock time",
       "after which reuse and drop act, likewise"},
      {"lockstep_step_on_input", &SO::lockstep_step_on_input, 0, 0, {}, "",
       "while the simulation thread waits for lockstep inputs, the thread that receives the last one takes the "
       "step, so that no sleeping thread is woken between an input and its step (docs/architecture.md, "
       "\"Threads\"); the same steps either way"},
  };
  return table;
}

namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Reflection;

Status CheckCount(const ServerOption& o, int64_t v) {
  if (v >= o.lo && v <= o.hi) return Status::Ok();
  const std::string range = o.hi >= INT_MAX ? ">= " + FormatValue(o.lo)
                                            : "between " + FormatValue(o.lo) + " and " + FormatValue(o.hi);
  return Status::InvalidArgument(std::string(o.name) + " must be " + range + ", got " + std::to_string(v));
}

Status CheckChoice(const ServerOption& o, const std::string& v) {
  std::string list;
  for (const char* c : o.choices) {
    if (v == c) return Status::Ok();
    list += std::string(list.empty() ? "" : ", ") + c;
  }
  return Status::InvalidArgument(std::string(o.name) + " must be one of " + list + ", got \"" + v + "\"");
}

// The choice's index, once CheckChoice has passed.
int IndexOf(const ServerOption& o, const std::string& v) {
  int i = 0;
  while (v != o.choices[i]) ++i;
  return i;
}

// One set field of the config into *options.
Status Read(const ServerOption& o, const proto::ServerConfig& config, const FieldDescriptor* fd, ServerOptions* out) {
  const Reflection* r = config.GetReflection();
  Status st;
  if (auto m = std::get_if<double SO::*>(&o.member)) {
    const double v = r->GetDouble(config, fd);
    if ((st = CheckInRange(o.name, v, o.lo, o.hi)).ok()) out->*(*m) = v;
  } else if (auto m = std::get_if<int SO::*>(&o.member)) {
    const int v = r->GetInt32(config, fd);
    if ((st = CheckCount(o, v)).ok()) out->*(*m) = v;
  } else if (auto m = std::get_if<int DL::*>(&o.member)) {
    const int v = r->GetInt32(config, fd);
    if ((st = CheckCount(o, v)).ok()) out->decode_limits.*(*m) = v;
  } else if (auto m = std::get_if<int64_t SO::*>(&o.member)) {
    const int64_t v = r->GetInt64(config, fd);
    if ((st = CheckCount(o, v)).ok()) out->*(*m) = v;
  } else if (auto m = std::get_if<bool SO::*>(&o.member)) {
    out->*(*m) = r->GetBool(config, fd);
  } else if (auto m = std::get_if<std::string SO::*>(&o.member)) {
    const std::string v = r->GetString(config, fd);
    if (o.choices.empty() || (st = CheckChoice(o, v)).ok()) out->*(*m) = v;
  } else if (auto m = std::get_if<RunMode SO::*>(&o.member)) {
    out->*(*m) = static_cast<RunMode>(r->GetEnumValue(config, fd));  // equal values by design
  } else if (auto m = std::get_if<FsyncPolicy SO::*>(&o.member)) {
    const std::string v = r->GetString(config, fd);
    if ((st = CheckChoice(o, v)).ok()) out->*(*m) = static_cast<FsyncPolicy>(IndexOf(o, v));
  } else if (auto m = std::get_if<LatePolicy SO::*>(&o.member)) {
    const std::string v = r->GetString(config, fd);
    if ((st = CheckChoice(o, v)).ok()) ParseLatePolicy(v, &(out->*(*m)));
  } else if (auto m = std::get_if<JointStatePolicy SO::*>(&o.member)) {
    const std::string v = r->GetString(config, fd);
    if ((st = CheckChoice(o, v)).ok()) out->*(*m) = static_cast<JointStatePolicy>(IndexOf(o, v));
  }
  return st;
}

// The value as the config file would spell it.
std::string Text(const ServerOption& o, const ServerOptions& options) {
  if (auto m = std::get_if<double SO::*>(&o.member)) return FormatValue(options.*(*m));
  if (auto m = std::get_if<int SO::*>(&o.member)) return std::to_string(options.*(*m));
  if (auto m = std::get_if<int DL::*>(&o.member)) return std::to_string(options.decode_limits.*(*m));
  if (auto m = std::get_if<int64_t SO::*>(&o.member)) return std::to_string(options.*(*m));
  if (auto m = std::get_if<bool SO::*>(&o.member)) return options.*(*m) ? "true" : "false";
  if (auto m = std::get_if<std::string SO::*>(&o.member)) return "\"" + options.*(*m) + "\"";
  if (auto m = std::get_if<RunMode SO::*>(&o.member)) return o.choices[static_cast<int>(options.*(*m)) - 1];
  if (auto m = std::get_if<FsyncPolicy SO::*>(&o.member)) {
    return "\"" + std::string(o.choices[static_cast<int>(options.*(*m))]) + "\"";
  }
  if (auto m = std::get_if<LatePolicy SO::*>(&o.member)) {
    return "\"" + std::string(LatePolicyName(options.*(*m))) + "\"";
  }
  if (auto m = std::get_if<JointStatePolicy SO::*>(&o.member)) {
    return "\"" + std::string(o.choices[static_cast<int>(options.*(*m))]) + "\"";
  }
  return "";
}

std::string Range(const ServerOption& o) {
  if (!o.choices.empty()) {
    std::string list;
    for (const char* c : o.choices) list += std::string(list.empty() ? "" : ", ") + c;
    return list;
  }
  if (o.lo == 0.0 && o.hi == 0.0) return "";
  if (o.hi >= INT_MAX) return ">= " + ReadableNumber(o.lo);
  return "[" + ReadableNumber(o.lo) + ", " + ReadableNumber(o.hi) + "]";
}

}  // namespace

Status ReadServerOptions(const proto::ServerConfig& config, ServerOptions* options, std::string* field) {
  const auto* descriptor = config.GetDescriptor();
  const Reflection* r = config.GetReflection();
  for (const ServerOption& o : ServerOptionTable()) {
    const FieldDescriptor* fd = descriptor->FindFieldByName(o.name);
    if (fd == nullptr || !r->HasField(config, fd)) continue;  // the test checks that every row has its field
    const Status st = Read(o, config, fd, options);
    if (!st.ok()) {
      if (field != nullptr) *field = o.name;
      return st;
    }
  }
  return Status::Ok();
}

const std::vector<const char*>& JointStateChoices() {
  static const std::vector<const char*> choices = {"always", "outside_lockstep", "off"};  // JointStatePolicy's order
  return choices;
}

bool ParseJointStatePolicy(const std::string& text, JointStatePolicy* policy) {
  const std::vector<const char*>& c = JointStateChoices();
  for (size_t i = 0; i < c.size(); ++i) {
    if (text == c[i]) {
      *policy = static_cast<JointStatePolicy>(i);
      return true;
    }
  }
  return false;
}

std::string ServerOptionsMarkdown() {
  const ServerOptions defaults;
  std::string md = "| option | default | range | unit | meaning |\n|---|---|---|---|---|\n";
  for (const ServerOption& o : ServerOptionTable()) {
    const std::string value = o.default_text != nullptr ? o.default_text : "`" + Text(o, defaults) + "`";
    md += "| `" + std::string(o.name) + "` | " + value + " | " + Range(o) + " | " + o.unit + " | " + o.doc + " |\n";
  }
  return md;
}

}  // namespace contactsim
