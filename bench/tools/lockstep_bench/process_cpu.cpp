#include "bench/tools/lockstep_bench/process_cpu.h"

#include <dirent.h>

#include <fstream>
#include <string>

namespace contactsim::bench {

ProcessSched ReadProcessSched(pid_t pid) {
  const std::string tasks = "/proc/" + std::to_string(pid) + "/task";
  DIR* dir = opendir(tasks.c_str());
  if (dir == nullptr) return {};
  ProcessSched s;
  while (const dirent* e = readdir(dir)) {
    if (e->d_name[0] == '.') continue;
    std::ifstream f(tasks + "/" + e->d_name + "/schedstat");
    double on_cpu = 0.0, waiting = 0.0, runs = 0.0;
    if (f >> on_cpu >> waiting >> runs) {
      s.cpu_seconds += on_cpu * 1e-9;
      s.runs += runs;
    }
  }
  closedir(dir);
  return s;
}

double ProcessCpuSeconds(pid_t pid) { return ReadProcessSched(pid).cpu_seconds; }

}  // namespace contactsim::bench
