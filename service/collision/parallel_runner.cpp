// oneTBB behind ParallelRunner (parallel_runner.h): a task_arena limited to
// the world's `threads`, and in it a task group of helpers that share the
// range with the caller in chunks.
#include "service/collision/parallel_runner.h"

#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "service/collision/region_probe.h"

namespace contactsim {

struct ParallelRunner::Arena {
  explicit Arena(int threads) : arena(threads) {}
  oneapi::tbb::task_arena arena;
};

int DefaultThreadCount() {
  const unsigned n = std::thread::hardware_concurrency();
  if (n == 0) return 1;
  return n > static_cast<unsigned>(kMaxThreads) ? kMaxThreads : static_cast<int>(n);
}

Status CheckThreadCount(int64_t threads) {
  if (threads >= 1 && threads <= kMaxThreads) return Status::Ok();
  return Status::InvalidArgument("threads must be between 1 and " + std::to_string(kMaxThreads) + ", got " +
                                 std::to_string(threads));
}

ParallelRunner::ParallelRunner(int threads) : threads_(threads) {
  const Status st = CheckThreadCount(threads);
  if (!st.ok()) {  // a programmer error: settings are checked at the boundary
    std::fprintf(stderr, "ParallelRunner: %s\n", st.message().c_str());
    std::abort();
  }
  if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
}

ParallelRunner::~ParallelRunner() = default;

void ParallelRunner::For(int n, int grain, const RangeFn& body) {
  if (n <= 0) return;
  const int chunk = grain > 0 ? grain : 1;
  if (arena_ == nullptr || n <= chunk) {
    const ParallelRegionProbe probe(n > chunk);  // more than a chunk: on the threads when there are more
    body(0, n, 0);
    return;
  }
  // self-scheduling: every thread takes the next `chunk` indices from one
  // counter until none are left. A helper the OS has descheduled (the
  // machine is shared) then holds back at most one chunk, where a split
  // range would leave the caller waiting for the helper's whole half.
  std::atomic<int> next{0};
  const auto drain = [&] {
    // the arena's slot: unique among its running threads, < threads_
    const int worker = oneapi::tbb::this_task_arena::current_thread_index();
    if (worker < 0 || worker >= threads_) {
      std::fprintf(stderr, "ParallelRunner: worker slot %d outside [0, %d)\n", worker, threads_);
      std::abort();
    }
    for (int begin = next.fetch_add(chunk); begin < n; begin = next.fetch_add(chunk)) {
      body(begin, std::min(begin + chunk, n), worker);
    }
  };
  const int helpers = std::min(threads_ - 1, (n - 1) / chunk);
  arena_->arena.execute([&] {
    oneapi::tbb::task_group group;
    for (int h = 0; h < helpers; ++h) group.run(drain);
    drain();
    // a helper not started yet runs here and finds nothing left
    group.wait();
  });
}

void ParallelRunner::RunTeam(const std::function<void(int worker)>& walk) {
  const auto run = [&] { walk(oneapi::tbb::this_task_arena::current_thread_index()); };
  arena_->arena.execute([&] {
    oneapi::tbb::task_group group;
    for (int h = 1; h < threads_; ++h) group.run(run);
    run();
    group.wait();
  });
}

}  // namespace contactsim
