// Runs the per-pair and per-body loops of a step on a world's own oneTBB
// task arena (docs/architecture.md, "Threads"). One arena per runner, and
// one runner per CollisionDetector, so that many worlds in one process each
// use at most their own `threads` and never the process's whole pool.
//
// Determinism: a loop body writes only its own index's slot (or scratch
// owned by its worker), so the result does not depend on how the range is
// split or which thread runs which part; callers combine the slots in index
// order afterwards.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

// Largest accepted `threads`: far above any machine we run on; a larger
// value is a typo, not a request.
constexpr int kMaxThreads = 256;

// std::thread::hardware_concurrency(), or 1 when the machine does not say:
// the default of the `threads` setting.
int DefaultThreadCount();

// Ok when 1 <= threads <= kMaxThreads; otherwise InvalidArgument naming the
// value ("threads must be between 1 and 256, got 0").
Status CheckThreadCount(int64_t threads);

class ParallelRunner {
 public:
  // `threads` must pass CheckThreadCount (an always-on check aborts
  // otherwise); 1 runs every loop serially on the caller, without oneTBB.
  explicit ParallelRunner(int threads = 1);
  ~ParallelRunner();
  ParallelRunner(const ParallelRunner&) = delete;
  ParallelRunner& operator=(const ParallelRunner&) = delete;

  int threads() const { return threads_; }

  // body(begin, end, worker) over disjoint ranges covering [0, n), each of
  // `grain` indices but the last; `worker` is in [0, threads()) and no two
  // calls running at the same time share it (so it may index per-worker
  // scratch). The caller works too. Runs body(0, n, 0) on the caller when
  // threads() is 1 or n <= grain. Returns when every index is done.
  using RangeFn = std::function<void(int begin, int end, int worker)>;
  void For(int n, int grain, const RangeFn& body);

  // A stage of Stages: fn(i, j) over disjoint ranges of [begin, end), each
  // of `grain` indices but the last, in any order and on any thread. The
  // function must outlive the Stages call.
  using StageFn = std::function<void(int begin, int end)>;
  struct Stage {
    const StageFn* fn = nullptr;
    int begin = 0, end = 0;
    int grain = 1;
  };
  // Runs the stages in order: no index of stage s starts before every
  // index of stage s - 1 is done (a barrier between stages, as in the
  // solver stages of Box2D v3). One call for a whole solve, so that the
  // threads meet at an atomic counter between stages instead of a task
  // launch per stage (parallel_stages.cpp says why no thread ever waits for
  // a particular other one). Serially in order when threads() is 1.
  void Stages(const std::vector<Stage>& stages);

 private:
  struct Arena;
  // `walk(worker)` on the caller and on threads() - 1 helper tasks of the
  // arena (worker: the arena slot, in [0, threads())); returns when all
  // have returned.
  void RunTeam(const std::function<void(int worker)>& walk);
  int threads_;
  std::unique_ptr<Arena> arena_;  // null when threads_ == 1
};

}  // namespace contactsim
