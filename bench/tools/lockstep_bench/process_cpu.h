// CPU time a process has used, all its threads together: the cost of a
// lockstep cycle or a ping-pong round trip in CPU rather than wall time. On
// a machine shared with other work, a cycle's wall time is mostly the
// wake-ups' wait for a core and moves by a factor of three from run to run;
// its CPU time moves far less. The count of times its threads were put on
// a CPU is the wake-ups (context switches in) a cycle costs.
#pragma once

#include <sys/types.h>

namespace contactsim::bench {

struct ProcessSched {
  double cpu_seconds = 0.0;  // on a CPU, every thread so far
  double runs = 0.0;         // times a thread was put on a CPU (its wake-ups and preemptions)

  ProcessSched operator+(const ProcessSched& o) const { return {cpu_seconds + o.cpu_seconds, runs + o.runs}; }
  ProcessSched operator-(const ProcessSched& o) const { return {cpu_seconds - o.cpu_seconds, runs - o.runs}; }
};

// The sums over every thread of process `pid` of
// /proc/<pid>/task/<tid>/schedstat's first (ns on a CPU) and third (runs)
// fields; zeros when it cannot be read.
ProcessSched ReadProcessSched(pid_t pid);

// ReadProcessSched(pid).cpu_seconds.
double ProcessCpuSeconds(pid_t pid);

}  // namespace contactsim::bench
