#include "bench/tools/scene_bench/scene_bench_main.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "bench/tools/scene_bench/bench_report.h"
#include "bench/tools/scene_bench/run_scene.h"

namespace contactsim::bench {
namespace {

// Redraws a one-line bar on stderr at most every 1% of the run.
class ProgressBar {
 public:
  explicit ProgressBar(int repeats) : repeats_(repeats) {}
  void operator()(int repeat, int step, int steps) {
    const int permille = static_cast<int>(1000.0 * (repeat * steps + step) / (double(repeats_) * steps));
    if (permille / 10 == last_ / 10 && step != steps) return;
    last_ = permille;
    constexpr int kWidth = 30;
    const int filled = permille * kWidth / 1000;
    std::fprintf(stderr, "\r[%s%s] %3d%%  repeat %d/%d  step %d/%d", std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, ' ').c_str(), permille / 10, repeat + 1, repeats_, step, steps);
    if (repeat + 1 == repeats_ && step == steps) std::fprintf(stderr, "\n");
  }
  void Finish() const { std::fprintf(stderr, "\n"); }

 private:
  int repeats_;
  int last_ = -10;
};

// The flags CLI11 cannot check alone: --threads with the engine's message,
// which names the value, and --param key=value into options->params.
// Returns "" when they are fine, else the line to print.
std::string CheckFlags(const std::vector<std::string>& params, BenchOptions* options) {
  if (const Status threads = CheckThreadCount(options->threads); !threads.ok()) {
    return "--threads: " + threads.message();
  }
  for (const std::string& p : params) {
    const size_t eq = p.find('=');
    if (eq == std::string::npos || eq == 0) return "--param must be key=value, got \"" + p + "\"";
    options->params[p.substr(0, eq)] = p.substr(eq + 1);
  }
  return "";
}

}  // namespace

int SceneBenchMain(int argc, char** argv, const RunnerInfo& info) {
  BenchOptions options;
  options.method = info.default_method;
  std::vector<std::string> params;
  bool list_methods = false;
  std::string known;
  for (const std::string& m : info.methods) known += (known.empty() ? "" : ", ") + m;

  CLI::App app{info.description};
  app.add_option("--scene", options.scene, "scene file (config/scenes/NAME.pbtxt)")->check(CLI::ExistingFile);
  app.add_option("--method", options.method, "method: " + known)->default_str(info.default_method);
  app.add_option("--param", params, "method parameter key=value (repeatable)");
  app.add_option("--steps", options.steps, "steps per repeat (default: the scene's `steps`)")
      ->check(CLI::PositiveNumber);
  app.add_option("--broadphase", options.broadphase, "sap or naive (contactsim only)")
      ->check(CLI::IsMember({"sap", "naive"}))
      ->default_str("sap");
  // checked below with the engine's own message, which names the value
  app.add_option("--threads", options.threads,
                 "threads of the collision detector (MuJoCo: of its thread pool), 1 to " +
                     std::to_string(kMaxThreads) + " (contactsim and MuJoCo only; Bullet and ODE use one)")
      ->default_str(std::to_string(options.threads) + ", the machine's hardware threads");
  app.add_flag("--sleep", options.sleep, "settled islands sleep, as in the server (contactsim only; default off, "
                                        "so that the solver is timed)");
  app.add_flag("--manifold-reuse,!--no-manifold-reuse", options.manifold_reuse,
               "touching boxes and hulls keep their manifolds while they move little, as the server's "
               "manifold_reuse option (contactsim only; default on, --no-manifold-reuse turns it off)");
  app.add_option("--repeat", options.repeat, "repeats; ms_per_step is their median")
      ->check(CLI::PositiveNumber)
      ->default_str("3");
  app.add_option("--max-seconds", options.max_seconds, "give up a repeat after this much stepping time (s; 0: never)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--json", options.json, "print one JSON object instead of a table");
  app.add_flag("--list-methods", list_methods, "print the method names, one a line, and exit");
  app.footer(info.engine == "contactsim"
                 ? "Without --scene, contactsim-bench runs its Google Benchmark micro benchmarks "
                   "(--benchmark_filter=REGEX, --benchmark_list_tests, ...)."
                 : "");
  CLI11_PARSE(app, argc, argv);

  if (list_methods) {
    for (const std::string& m : info.methods) std::cout << m << "\n";
    return 0;
  }
  if (options.scene.empty() || options.method.empty()) {
    std::cerr << "--scene and --method are required (methods: " << known << "); see --help\n";
    return 1;
  }
  if (const std::string error = CheckFlags(params, &options); !error.empty()) {
    std::cerr << error << "\n";
    return 1;
  }

  SceneSpec scene;
  World world;
  Status st = LoadSceneFile(options.scene, &scene);
  if (st.ok()) st = BuildWorld(scene, &world);
  if (st.ok() && options.steps == 0 && scene.steps == 0) {
    st = Status::InvalidArgument(options.scene + ": the scene has no `steps`; give --steps N");
  }
  BenchResult result;
  if (st.ok()) {
    ProgressBar bar(options.repeat);
    ProgressFn progress;
    if (!options.json) progress = [&bar](int repeat, int step, int steps) { bar(repeat, step, steps); };
    result = RunScene(options, scene, world, info.factory, progress);
    if (!options.json && result.status != "ok") bar.Finish();
  } else {
    result.method = options.method;
    result.status = "error: " + st.message();
  }
  result.engine = info.engine;
  result.threads = info.threaded ? options.threads : 1;  // Bullet and ODE step on one thread
  result.sleep = info.engine == "contactsim" && options.sleep;
  result.manifold_reuse = info.engine == "contactsim" && options.manifold_reuse;
  if (options.json) {
    std::cout << ToJson(result) << std::endl;
  } else {
    PrintTable(result, std::cout);
  }
  return result.status == "ok" ? 0 : 1;
}

}  // namespace contactsim::bench
