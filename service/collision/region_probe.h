// A measurement aid for the serial share of a step (BENCHMARKS.md, "Serial
// loops of a step"): in a build with -DCONTACTSIM_REGION_PROBE=ON, the code
// that runs on the threads when there are two or more (a ParallelRunner::For
// of more than one chunk, a stage of more than one chunk, the narrowphase's
// and sweep and prune's loops) switches callgrind's collection off on the
// way in and back on the way out, so that on one thread a callgrind run
// counts the serial instructions of a step only, and one started with
// --collect-atstart=no the parallel ones. 2 / (1 + f), f the serial share,
// bounds what two threads can gain (Amdahl). Nested regions toggle once. In
// every other build the probe is empty.
#pragma once

#ifdef CONTACTSIM_REGION_PROBE
#include <valgrind/callgrind.h>
#endif

namespace contactsim {

class ParallelRegionProbe {
 public:
  // `parallel`: the code until the probe's end would run on the threads.
  explicit ParallelRegionProbe(bool parallel) {
#ifdef CONTACTSIM_REGION_PROBE
    on_ = parallel;
    if (on_ && Depth()++ == 0) CALLGRIND_TOGGLE_COLLECT;
#else
    (void)parallel;
#endif
  }
  ~ParallelRegionProbe() {
#ifdef CONTACTSIM_REGION_PROBE
    if (on_ && --Depth() == 0) CALLGRIND_TOGGLE_COLLECT;
#endif
  }
  ParallelRegionProbe(const ParallelRegionProbe&) = delete;
  ParallelRegionProbe& operator=(const ParallelRegionProbe&) = delete;

 private:
#ifdef CONTACTSIM_REGION_PROBE
  static int& Depth() {
    static thread_local int depth = 0;
    return depth;
  }
  bool on_ = false;
#endif
};

}  // namespace contactsim
