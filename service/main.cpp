// contactsim-server: owns one physics world and serves it over LCM.
//
//   contactsim-server --config FILE [--scene FILE] [--lcm-url URL] [--prefix NAME]
//                     [--log-level LEVEL] [--mode realtime|free_run|lockstep] [--paused] [--no-live-line]
//                     [--journal DIR] [--auth-key-file FILE] [--replay LOG]
//
// With --replay LOG it serves nothing: it re-simulates a run recorded with
// lcm-logger from the same config and scene and compares state hashes
// (service/server/log_replay.h); exit code 0 identical, 2 diverged.
//
// Two threads: this one runs the simulation loop (SimServer::Run), a second
// one receives LCM messages and hands them to the server, and takes the
// loop's turn while the loop waits for lockstep inputs (sim_server.h).
// SIGINT and SIGTERM stop both cleanly.
#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <csignal>
#include <thread>

#include "service/server/lcm_transport.h"
#include "service/server/log_replay.h"
#include "service/server/server_config.h"
#include "service/server/signing_transport.h"
#include "service/server/sim_server.h"

namespace {

std::atomic<bool> g_stop{false};

void OnSignal(int) { g_stop.store(true); }

}  // namespace

int main(int argc, char** argv) {
  using namespace contactsim;
  CLI::App app{"contactsim-server: rigid-body contact co-simulation over LCM"};
  std::string config_path, scene_path, lcm_url, prefix, log_level, mode, journal_dir, replay_log, auth_key_file,
      joint_state;
  bool paused = false, no_live_line = false;
  app.add_option("--config", config_path, "server configuration (protobuf text)")->required();
  app.add_option("--scene", scene_path, "scene file, overriding the config's");
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else the project default)");
  app.add_option("--prefix", prefix, "channel prefix (default from config: CONTACTSIM)");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical, off");
  app.add_option("--mode", mode, "realtime, free_run or lockstep")
      ->check([](const std::string& name) {
        RunMode m;
        return ParseRunMode(name, &m) ? std::string() : std::string("must be realtime, free_run or lockstep");
      });
  app.add_option("--joint-state", joint_state,
                 "always, outside_lockstep or off: when JOINT_STATE is published beside STATE (config joint_state)")
      ->check([](const std::string& name) {
        JointStatePolicy p;
        return ParseJointStatePolicy(name, &p) ? std::string() : std::string("must be always, outside_lockstep or off");
      });
  app.add_flag("--paused", paused, "start paused");
  app.add_flag("--no-live-line", no_live_line, "do not print the progress line");
  app.add_option("--auth-key-file", auth_key_file, "shared key: commands must be signed with it (config auth_key_file)");
  app.add_option("--journal", journal_dir, "journal and snapshot folder; recovers from it when it holds a snapshot");
  std::vector<std::string> model_paths;
  app.add_option("--model-path", model_paths,
                 "a folder of model files and their meshes (repeatable; searched before the config's model_path)");
  app.add_option("--replay", replay_log,
                 "re-simulate an lcm-logger log of a run from this config and scene; report the first divergent step");
  CLI11_PARSE(app, argc, argv);
  // a file size limit makes journal writes fail (answered INTERNAL), not the server die
  std::signal(SIGXFSZ, SIG_IGN);

  auto logger = spdlog::stderr_color_mt("contactsim");
  spdlog::set_default_logger(logger);

  proto::ServerConfig config;
  Status st = LoadServerConfig(config_path, &config);
  ServerSetup setup;
  if (st.ok()) st = MakeServerSetup(config, config_path, scene_path, &setup);
  if (!st.ok()) {
    spdlog::critical("{}", st.message());
    return 1;
  }
  if (!prefix.empty()) setup.options.prefix = prefix;
  if (!lcm_url.empty()) setup.lcm_url = lcm_url;
  if (!log_level.empty()) setup.log_level = log_level;
  if (!mode.empty()) {
    ParseRunMode(mode, &setup.options.mode);  // checked by CLI11
  }
  if (!joint_state.empty()) ParseJointStatePolicy(joint_state, &setup.options.joint_state);  // checked by CLI11
  if (paused) setup.options.start_paused = true;
  if (no_live_line) setup.options.live_line = false;
  if (!journal_dir.empty()) setup.options.journal_dir = journal_dir;
  setup.options.model_path_flags = model_paths;
  if (!auth_key_file.empty()) {
    std::string error;
    if (!LoadAuthKey(auth_key_file, &setup.options.auth_key, &error)) {
      spdlog::critical("--auth-key-file: {}", error);
      return 1;
    }
  }
  const auto level = spdlog::level::from_str(setup.log_level);
  if (level == spdlog::level::off && setup.log_level != "off") {
    spdlog::critical("--log-level must be one of trace, debug, info, warn, error, critical, off, got \"{}\"",
                     setup.log_level);
    return 1;
  }
  spdlog::set_level(level);
  if (!replay_log.empty()) return RunReplay(std::move(setup), replay_log);

  const std::string url = ResolveLcmUrl(setup.lcm_url);
  LcmTransport transport(url);
  if (!transport.good()) {
    spdlog::critical("cannot open LCM at {} (no multicast route? see README, troubleshooting)", url);
    return 1;
  }
  // with a key, everything the server publishes is signed (docs/protocol.md)
  SigningTransport signing(&transport, setup.options.auth_key);
  Transport* out = setup.options.auth_key.empty() ? static_cast<Transport*>(&transport) : &signing;
  // Stop requests are caught from before Init on: Init announces the
  // server and recovers its journal, and a client that has seen either may
  // stop it at once; Run then returns at its first look at g_stop.
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  SimServer server(setup.options, out);
  // Subscribe before Init announces the server (STATUS): LCM opens its
  // receive socket on the first subscribe, and a client may answer the
  // announcement at once.
  for (const std::string& channel : server.CommandChannelNames()) {
    transport.Subscribe(channel, [&](const std::string& c, const void* d, int n) { server.OnMessage(c, d, n); });
  }
  if (!(st = server.Init(setup.scene.get(), setup.method)).ok()) {
    spdlog::critical("{}", st.message());
    return 1;
  }

  spdlog::info("contactsim-server {} ready: {} bodies, method {}, {} threads, {} mode{}, channels {}_*, LCM {}",
               CONTACTSIM_VERSION, server.world().bodies().size(), server.method().Name(), setup.options.threads,
               NameOf(setup.options.mode),
               setup.options.start_paused ? " (paused)" : "", setup.options.prefix, url);

  std::thread lcm_thread([&] {
    while (!g_stop.load()) transport.HandleTimeout(100);
  });
  server.Run(g_stop);
  lcm_thread.join();
  spdlog::info("stopped cleanly at step {} (t = {:.3f} s)", server.world().step, server.world().time);
  return 0;
}
