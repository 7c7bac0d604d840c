#include "bench/tools/lockstep_bench/process_cpu.h"

#include <dirent.h>

#include <fstream>
#include <string>

namespace contactsim::bench {

double ProcessCpuSeconds(pid_t pid) {
  const std::string tasks = "/proc/" + std::to_string(pid) + "/task";
  DIR* dir = opendir(tasks.c_str());
  if (dir == nullptr) return 0.0;
  double ns = 0.0;
  while (const dirent* e = readdir(dir)) {
    if (e->d_name[0] == '.') continue;
    std::ifstream f(tasks + "/" + e->d_name + "/schedstat");
    double on_cpu = 0.0;
    if (f >> on_cpu) ns += on_cpu;
  }
  closedir(dir);
  return ns * 1e-9;
}

}  // namespace contactsim::bench
