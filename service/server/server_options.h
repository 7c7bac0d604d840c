// The server's options, declared once: each is a member of ServerOptions
// whose initial value is its default, and a row of ServerOptionTable() that
// names its field in the config file (service/proto/config.proto), its range
// or choices, unit and one line of doc, as a contact method declares its
// parameters (service/contact/param_table.h). The table reads a config,
// taking only the fields the file sets (an absent field keeps the default),
// and writes docs/configuration.md's table (tests/server/server_options_test.cpp
// compares).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "service/collision/manifold_cache.h"
#include "service/collision/parallel_runner.h"
#include "service/proto/config.pb.h"
#include "service/server/arm_driver/arm_driver_config.h"
#include "service/server/arm_driver/wsg_driver_config.h"
#include "service/server/command.h"
#include "service/server/command_channels.h"
#include "service/server/journal.h"
#include "service/server/lockstep.h"

namespace contactsim {

// When JOINT_STATE goes out beside STATE, whose joint block carries the same
// joints (docs/actuators.md, "Joint channels"); the config's choices in order.
enum class JointStatePolicy { kAlways, kOutsideLockstep, kOff };

struct ServerOptions {
  std::string prefix = "CONTACTSIM";
  RunMode mode = RunMode::kRealtime;
  double real_time_factor = 1.0;
  bool start_paused = false;
  double state_rate_hz = 60.0;
  double contacts_rate_hz = 30.0;
  double status_rate_hz = 1.0;
  std::string broadphase = "sap";
  int threads = DefaultThreadCount();
  bool sleep = true;
  bool manifold_reuse = kManifoldReuseDefault;
  int max_bodies = 100000;
  int max_joints = 100000;
  DecodeLimits decode_limits;  // its members are rows of the table too
  double max_commands_per_second = 5000.0;
  double command_burst = 10000.0;
  int max_queued_commands = 20000;
  std::string auth_key;        // read from the config's auth_key_file; "" = no signatures
  double auth_window_s = 30.0;
  bool live_line = true;
  JointStatePolicy joint_state = JointStatePolicy::kOutsideLockstep;
  std::vector<std::string> model_paths;       // the config's model_path, from the config's folder
  std::vector<std::string> model_path_flags;  // not in the config: --model-path's, searched first
  std::string journal_dir;     // the config's journal_dir, from the config's folder; "" = none on disk
  FsyncPolicy journal_fsync = FsyncPolicy::kAlways;
  int64_t snapshot_every = 2400;
  int max_snapshots = 32;
  LatePolicy late_policy = LatePolicy::kWait;
  double late_timeout = 0.1;
  bool lockstep_step_on_input = true;
  std::optional<ArmDriverConfig> arm_driver;  // the config's arm_driver block, checked
  std::optional<WsgDriverConfig> wsg_driver;  // the config's wsg_driver block, checked
  bool write_files = true;     // not in the config: false (a replay) makes SNAPSHOT to a file write nothing
};

// One option: the config field that sets it and where it lands.
struct ServerOption {
  using Member = std::variant<double ServerOptions::*, int ServerOptions::*, int64_t ServerOptions::*,
                              bool ServerOptions::*, std::string ServerOptions::*, int DecodeLimits::*,
                              RunMode ServerOptions::*, FsyncPolicy ServerOptions::*, LatePolicy ServerOptions::*,
                              JointStatePolicy ServerOptions::*>;
  const char* name;  // the field of proto::ServerConfig
  Member member;
  double lo, hi;                      // numbers: the range
  std::vector<const char*> choices;   // words: the ones accepted
  const char* unit;
  const char* doc;
  const char* default_text = nullptr;  // the docs' default when not the value (threads: the machine's)
};

const std::vector<ServerOption>& ServerOptionTable();

// Reads every table field that `config` sets into *options, checked
// against its range or choices; the first error names the field and the
// value, and *field (when given) is its name.
Status ReadServerOptions(const proto::ServerConfig& config, ServerOptions* options, std::string* field = nullptr);

// The joint_state option's words, in JointStatePolicy's order (the table's
// and the --joint-state flag's choices), and one word into the policy.
const std::vector<const char*>& JointStateChoices();
bool ParseJointStatePolicy(const std::string& text, JointStatePolicy* policy);

// docs/configuration.md's table: option, default, range or choices, unit, doc.
std::string ServerOptionsMarkdown();

}  // namespace contactsim
