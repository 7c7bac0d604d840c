// CPU time a process has used, all its threads together: the cost of a
// lockstep cycle or a ping-pong round trip in CPU rather than wall time. On
// a machine shared with other work, a cycle's wall time is mostly the
// wake-ups' wait for a core and moves by a factor of three from run to run;
// its CPU time moves far less.
#pragma once

#include <sys/types.h>

namespace contactsim::bench {

// Seconds on a CPU of every thread of process `pid` so far (the first field
// of /proc/<pid>/task/<tid>/schedstat, ns); 0 when it cannot be read.
double ProcessCpuSeconds(pid_t pid);

}  // namespace contactsim::bench
