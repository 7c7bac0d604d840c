// contactsim-bench-lockstep (`make bench-lockstep`): lockstep cycles per
// second with one controller, for 1 and 100 bodies and for a 7-DoF arm
// driven through joint commands (arm_lockstep.h), beside a raw LCM
// ping-pong between two processes measured in the same run (the
// transport's own limit; lcm_ping_pong.h). Every party is its own process:
// the server (contactsim-server beside this binary), the controller (this
// process, contactsim::Controller) and the pong (this binary, --pong).
// Each row also gives the CPU time of a cycle (server and controller) and of
// a round trip (ping and pong), which the machine's load moves far less than
// the rates (process_cpu.h).
//
//   contactsim-bench-lockstep [--config FILE] [--bodies 1,100] [--arm URDF] [--seconds S] [--lcm-url URL]
//                             [--joint-state always|outside_lockstep|off]
//
// A benchmark, not a test: it prints numbers and asserts none.
#include <CLI/CLI.hpp>
#include <contactsim/input_t.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fcntl.h>
#include <string>
#include <thread>
#include <vector>

#include "bench/tools/lockstep_bench/arm_lockstep.h"
#include "bench/tools/lockstep_bench/lcm_ping_pong.h"
#include "bench/tools/lockstep_bench/process_cpu.h"
#include "contactsim/client.h"
#include "contactsim/controller.h"

namespace {

using namespace contactsim;
using Clock = std::chrono::steady_clock;

std::string SelfPath() {
  std::vector<char> buf(4096);
  const ssize_t n = readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  return n > 0 ? std::string(buf.data(), static_cast<size_t>(n)) : std::string();
}

// Starts argv[0] with argv; its output goes to /dev/null when `quiet`.
pid_t Spawn(const std::vector<std::string>& args, bool quiet) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  if (quiet) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, STDOUT_FILENO);
    dup2(null, STDERR_FILENO);
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  _exit(127);
}

// SIGINT (when asked), then waits up to 10 s, then SIGKILL.
void Reap(pid_t pid, bool interrupt) {
  if (interrupt) kill(pid, SIGINT);
  for (int i = 0; i < 100; ++i) {
    if (waitpid(pid, nullptr, WNOHANG) == pid) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}

struct LockstepResult {
  double cycles_per_second = 0.0;
  double cpu_per_cycle = 0.0;   // s on a CPU, the server's and this process's together
  double runs_per_cycle = 0.0;  // times their threads were put on a CPU (process_cpu.h)
  int state_bytes = 0, input_bytes = 0;
  std::string error;
};

// n spheres resting on a plane in a grid (contacts, no motion to speak of),
// one controller pushing body 1 with zero force: each cycle is one STATE of
// n bodies and one input of one body.
LockstepResult MeasureLockstep(Client& client, int bodies, double seconds, pid_t server) {
  LockstepResult r;
  auto fail = [&](const char* what, const CommandResult& c) {
    r.error = std::string(what) + ": " + ToString(c);
    return r;
  };
  CommandResult c;
  if (!(c = client.Pause()).ok()) return fail("pause", c);
  if (!(c = client.Reset()).ok()) return fail("reset", c);
  if (!(c = client.AddPlane(Eigen::Vector3d::UnitZ(), 0.0).status).ok()) return fail("add plane", c);
  const int side = static_cast<int>(std::ceil(std::sqrt(bodies)));
  int64_t first = 0;
  for (int i = 0; i < bodies; ++i) {
    BodyOptions o;
    o.position = Eigen::Vector3d(0.2 * (i % side), 0.2 * (i / side), 0.05);
    o.mass = 1.0;
    const auto id = client.AddSphere(0.05, o);
    if (!id.status.ok()) return fail("add sphere", id.status);
    if (i == 0) first = id.value;
  }
  if (!(c = client.Step(10)).ok()) return fail("step", c);
  const auto state = client.LatestState();
  r.state_bytes = state ? state->getEncodedSize() : 0;
  input_t in{};
  in.client_id = client.client_id();
  in.num_bodies = 1;
  in.body_ids = {first};
  in.forces = {{0.0, 0.0, 0.0}};
  in.torques = {{0.0, 0.0, 0.0}};
  r.input_bytes = in.getEncodedSize();

  Controller controller(client, [first](const state_t&) { return BodyInputs{{first, BodyWrench{}}}; });
  if (!(c = controller.Start(LatePolicy::kWait)).ok()) return fail("register controller", c);
  if (!(c = client.SetMode(Mode::kLockstep)).ok() || !(c = client.Resume()).ok()) return fail("lockstep", c);
  const int64_t warm = (state ? state->step : 0) + 50;
  if (!controller.WaitForStep(warm, std::chrono::seconds(30))) {
    r.error = "lockstep did not reach step " + std::to_string(warm);
    return r;
  }
  const bench::ProcessSched sched0 = bench::ReadProcessSched(server) + bench::ReadProcessSched(getpid());
  const int64_t s0 = controller.answered();
  const auto t0 = Clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const int64_t s1 = controller.answered();
  const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
  const bench::ProcessSched spent =
      bench::ReadProcessSched(server) + bench::ReadProcessSched(getpid()) - sched0;
  r.cycles_per_second = (s1 - s0) / elapsed;
  r.cpu_per_cycle = s1 > s0 ? spent.cpu_seconds / (s1 - s0) : 0.0;
  r.runs_per_cycle = s1 > s0 ? spent.runs / (s1 - s0) : 0.0;
  client.Pause();
  controller.Stop();
  client.SetMode(Mode::kFreeRun);
  return r;
}

// The ping-pong of `ping_bytes` pings and `pong_bytes` pongs against a
// pong process of its own; false if the pong never answered. *trip: CPU
// and runs per round trip, both processes together (with the pong's start).
bool PingPong(const std::string& self, const std::string& url, const std::string& channel, int ping_bytes,
              int pong_bytes, double seconds, bench::PingPongResult* pp, bench::ProcessSched* trip) {
  const pid_t pong = Spawn({self, "--lcm-url", url, "--pong", channel, "--pong-bytes", std::to_string(pong_bytes)},
                           false);
  const bench::ProcessSched sched0 = bench::ReadProcessSched(getpid());
  const bool ok = bench::RunPing(url, channel, ping_bytes, seconds, 20.0, pp);
  const bench::ProcessSched spent = bench::ReadProcessSched(getpid()) - sched0 + bench::ReadProcessSched(pong);
  Reap(pong, !ok);
  const double n = pp->round_trips > 0 ? static_cast<double>(pp->round_trips) : 0.0;
  *trip = n > 0 ? bench::ProcessSched{spent.cpu_seconds / n, spent.runs / n} : bench::ProcessSched{};
  return ok;
}

// One row of the table: the rates, their ratio, and the CPU of a cycle and
// of a round trip (microseconds) and theirs.
void PrintRow(const std::string& world, int bytes, double cycles, double cycle_cpu, double cycle_runs, double trips,
              const bench::ProcessSched& trip) {
  std::printf("| %s | %d | %.0f | %.0f | %.2f | %.0f | %.0f | %.2f | %.1f | %.1f |\n", world.c_str(), bytes, cycles,
              trips, cycles / trips, 1e6 * cycle_cpu, 1e6 * trip.cpu_seconds,
              cycle_cpu > 0.0 ? trip.cpu_seconds / cycle_cpu : 0.0, cycle_runs, trip.runs);
  std::fflush(stdout);
}

// The arm row: its lockstep rate beside a ping-pong of the same sizes
// (what the server sends a cycle, the input back); 0, or 1 on failure.
int MeasureArmRow(Client& client, const std::string& self, const std::string& url, const std::string& prefix,
                  const std::string& urdf, double seconds, pid_t server) {
  const bench::ArmLockstepResult arm = bench::MeasureArmLockstep(client, urdf, seconds, server);
  if (!arm.error.empty()) {
    std::fprintf(stderr, "arm %s: %s\n", urdf.c_str(), arm.error.c_str());
    return 1;
  }
  bench::PingPongResult pp;
  bench::ProcessSched trip;
  if (!PingPong(self, url, prefix + "_PPARM", arm.state_bytes, arm.input_bytes, seconds, &pp, &trip)) {
    std::fprintf(stderr, "arm: the pong process never answered\n");
    return 1;
  }
  PrintRow(std::to_string(arm.joints) + "-joint arm, joint commands" +
               (arm.joint_states_per_cycle > 0.5 ? " (+ JOINT_STATE)" : ""),
           arm.state_bytes, arm.cycles_per_second, arm.cpu_per_cycle, arm.runs_per_cycle, pp.per_second(), trip);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"contactsim-bench-lockstep: lockstep cycles per second beside a raw LCM ping-pong"};
  std::string config = CONTACTSIM_SOURCE_DIR "/config/server.pbtxt", url, pong_channel;
  std::vector<int> body_counts{1, 100};
  double seconds = 3.0;
  int pong_bytes = 0;
  app.add_option("--config", config, "server configuration");
  app.add_option("--bodies", body_counts, "body counts to measure")->delimiter(',');
  app.add_option("--seconds", seconds, "measuring time per row and kind (s)");
  std::string arm = CONTACTSIM_SOURCE_DIR "/.venv/lib/python3.11/site-packages/pybullet_data/kuka_iiwa/model.urdf";
  app.add_option("--arm", arm, "a fixed-base arm's URDF driven by joint commands (\"\": none)");
  app.add_option("--lcm-url", url, "LCM URL (default: $LCM_DEFAULT_URL, else the project default)");
  std::string joint_state;
  app.add_option("--joint-state", joint_state, "the server's --joint-state (default: the config's joint_state)");
  app.add_option("--pong", pong_channel, "internal: run as the pong process on this channel");
  app.add_option("--pong-bytes", pong_bytes, "internal: pong payload size");
  CLI11_PARSE(app, argc, argv);
  url = ResolveLcmUrl(url);
  if (!pong_channel.empty()) return bench::RunPong(url, pong_channel, pong_bytes, 30.0);

  const std::string self = SelfPath();
  const std::string server_bin = self.substr(0, self.rfind('/') + 1) + "contactsim-server";
  const std::string prefix = "LOCKSTEP_BENCH_" + std::to_string(getpid());
  std::printf("lockstep cycles per second, one C++ controller, %g s per measurement, LCM %s\n\n", seconds,
              url.c_str());
  std::printf("| world | bytes out a cycle | lockstep cycles/s | LCM ping-pong round trips/s | lockstep / ping-pong | "
              "CPU us/cycle (server + controller) | CPU us/round trip (both ends) | ping-pong / lockstep CPU | "
              "runs/cycle | runs/round trip |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::fflush(stdout);

  std::vector<std::string> server_args = {server_bin, "--config",       config, "--lcm-url", url, "--prefix", prefix,
                                          "--mode",   "free_run",     "--paused", "--no-live-line", "--log-level",
                                          "warn"};
  if (!joint_state.empty()) server_args.insert(server_args.end(), {"--joint-state", joint_state});
  const pid_t server = Spawn(server_args, true);
  ClientOptions options;
  options.url = url;
  options.prefix = prefix;
  options.reply_timeout = std::chrono::milliseconds(10000);
  int rc = 0;
  {
    Client client(options);
    if (!client.WaitForServer(std::chrono::seconds(20))) {
      std::fprintf(stderr, "no STATUS from %s within 20 s\n", server_bin.c_str());
      Reap(server, true);
      return 1;
    }
    for (int n : body_counts) {
      const LockstepResult ls = MeasureLockstep(client, n, seconds, server);
      if (!ls.error.empty()) {
        std::fprintf(stderr, "%d bodies: %s\n", n, ls.error.c_str());
        rc = 1;
        break;
      }
      // the transport alone, between two processes, with the same sizes
      bench::PingPongResult pp;
      bench::ProcessSched trip;
      if (!PingPong(self, url, prefix + "_PP" + std::to_string(n), ls.state_bytes, ls.input_bytes, seconds, &pp,
                    &trip)) {
        std::fprintf(stderr, "%d bodies: the pong process never answered\n", n);
        rc = 1;
        break;
      }
      PrintRow(std::to_string(n) + " bodies", ls.state_bytes, ls.cycles_per_second, ls.cpu_per_cycle,
               ls.runs_per_cycle, pp.per_second(), trip);
      if (pp.resends > 0) std::printf("(%lld ping(s) resent after 1 s: lost on UDP)\n", static_cast<long long>(pp.resends));
      std::fflush(stdout);
    }
    if (rc == 0 && !arm.empty() && access(arm.c_str(), R_OK) != 0) {
      std::printf("(no arm row: %s is not readable; pip install pybullet, or pass --arm)\n", arm.c_str());
    } else if (rc == 0 && !arm.empty()) {
      rc = MeasureArmRow(client, self, url, prefix, arm, seconds, server);
    }
  }
  Reap(server, true);
  return rc;
}
