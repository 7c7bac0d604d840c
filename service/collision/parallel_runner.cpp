// oneTBB behind ParallelRunner (parallel_runner.h): a task_arena limited to
// the world's `threads`, a parallel_for over blocked ranges inside it.
#include "service/collision/parallel_runner.h"

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

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
  if (arena_ == nullptr || n <= grain) {
    body(0, n, 0);
    return;
  }
  arena_->arena.execute([&] {
    oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<int>(0, n, grain > 0 ? grain : 1),
                              [&](const oneapi::tbb::blocked_range<int>& r) {
                                // the arena's slot: unique among its running threads, < threads_
                                const int worker = oneapi::tbb::this_task_arena::current_thread_index();
                                if (worker < 0 || worker >= threads_) {
                                  std::fprintf(stderr, "ParallelRunner: worker slot %d outside [0, %d)\n", worker,
                                               threads_);
                                  std::abort();
                                }
                                body(r.begin(), r.end(), worker);
                              });
  });
}

}  // namespace contactsim
