// The command line shared by contactsim-bench's scene mode and the peer
// runners (bench/peers), so that all of them take the same flags:
//   TOOL --scene config/scenes/NAME.pbtxt --method NAME [--param key=value ...]
//        [--steps N] [--broadphase sap|naive] [--threads N] [--sleep] [--repeat 3] [--max-seconds S] [--json]
//        [--list-methods]
// Exit status: 0 when the run completed ("status": "ok"), 1 otherwise (bad
// arguments, a scene or parameter error, NaN, explosion, time limit); with
// --json the JSON object is printed in every case but a usage error.
#pragma once

#include <string>
#include <vector>

#include "bench/tools/scene_bench/scene_engine.h"

namespace contactsim::bench {

struct RunnerInfo {
  std::string engine;                // "contactsim", "bullet", ...
  std::string description;           // first line of --help
  std::string default_method;        // empty: --method is required
  std::vector<std::string> methods;  // for --list-methods and the help
  bool threaded = false;             // steps on --threads threads (else on one, whatever --threads says)
  EngineFactory factory;
};

int SceneBenchMain(int argc, char** argv, const RunnerInfo& info);

}  // namespace contactsim::bench
