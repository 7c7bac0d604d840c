// ParallelRunner::Stages (parallel_runner.h): every thread, the caller and
// `threads - 1` helper tasks, walks the same list of stages and takes
// chunks of the current stage from its counter; a thread moves on to stage
// s only when stage s - 1's done counter reaches its size. Nobody waits for
// a particular thread, only for chunks someone has taken and is running:
// the caller alone finishes everything when no helper starts (another world
// in the process may hold the pool's workers), so this cannot deadlock, and
// a helper that starts late skips the stages already done. The stages'
// functions write what their index owns (a colour's blocks share no body:
// block_colours.h), so the result does not depend on who ran what.
#include <algorithm>
#include <atomic>
#include <memory>
#include <thread>

#include "service/collision/parallel_runner.h"
#include "service/collision/region_probe.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define CONTACTSIM_PAUSE() _mm_pause()
#else
#define CONTACTSIM_PAUSE() ((void)0)
#endif

namespace contactsim {
namespace {

// One stage's counters, on their own cache line so that threads taking
// chunks of one stage do not slow the readers of another.
struct alignas(64) StageCounters {
  std::atomic<int> done{0};  // indices finished
};

// Spins briefly, then yields: the threads of a stage wait a few
// microseconds, but on a shared machine the thread they wait for may have
// lost its core.
void WaitUntilDone(const std::atomic<int>& done, int size) {
  for (int spins = 0; done.load(std::memory_order_acquire) < size; ++spins) {
    if (spins < 2000) {
      CONTACTSIM_PAUSE();
    } else {
      std::this_thread::yield();
    }
  }
}

// The stage's chunks: `grain` indices each, the last one shorter.
int ChunkCount(const ParallelRunner::Stage& stage) {
  const int size = stage.end - stage.begin;
  return size <= 0 ? 0 : (size + stage.grain - 1) / stage.grain;
}

// Worker w of T starts at chunk w C / T of a stage's C and walks on
// (wrapping around), taking each chunk nobody has claimed yet: each thread
// first takes its own contiguous share, the same share of a colour or of the
// bodies pass after pass, so its data stay in its core's cache; then it
// helps with what is left of the others', and a thread that arrives late
// finds its share done.
void RunStageList(const std::vector<ParallelRunner::Stage>& stages, const std::vector<int>& first_chunk,
                  std::atomic<char>* claimed, StageCounters* counters, int worker, int threads) {
  for (size_t s = 0; s < stages.size(); ++s) {
    if (s > 0) WaitUntilDone(counters[s - 1].done, stages[s - 1].end - stages[s - 1].begin);
    const ParallelRunner::Stage& stage = stages[s];
    const int chunks = ChunkCount(stage);
    for (int k = 0; k < chunks; ++k) {
      const int chunk = (worker * chunks / threads + k) % chunks;
      if (claimed[first_chunk[s] + chunk].exchange(1, std::memory_order_relaxed) != 0) continue;
      const int i = stage.begin + chunk * stage.grain;
      const int j = std::min(i + stage.grain, stage.end);
      (*stage.fn)(i, j);
      counters[s].done.fetch_add(j - i, std::memory_order_release);
    }
  }
}

}  // namespace

void ParallelRunner::Stages(const std::vector<Stage>& stages) {
  if (threads_ == 1) {
    for (const Stage& stage : stages) {
      const ParallelRegionProbe probe(stage.end - stage.begin > stage.grain);  // more than one chunk
      if (stage.end > stage.begin) (*stage.fn)(stage.begin, stage.end);
    }
    return;
  }
  std::vector<Stage> sized(stages);
  std::vector<int> first_chunk(stages.size());
  int chunks = 0;
  for (size_t s = 0; s < sized.size(); ++s) {
    sized[s].grain = std::max(std::min(sized[s].grain, sized[s].end - sized[s].begin), 1);
    first_chunk[s] = chunks;
    chunks += ChunkCount(sized[s]);
  }
  std::unique_ptr<StageCounters[]> counters(new StageCounters[sized.size()]);
  std::unique_ptr<std::atomic<char>[]> claimed(new std::atomic<char>[chunks]);
  for (int c = 0; c < chunks; ++c) claimed[c].store(0, std::memory_order_relaxed);
  RunTeam([&](int worker) {
    RunStageList(sized, first_chunk, claimed.get(), counters.get(), worker, threads_);
  });
}

}  // namespace contactsim
