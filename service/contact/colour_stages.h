// The stage list of a solver whose passes sweep coloured blocks
// (block_colours.h) on ParallelRunner::Stages: soft's and xpbd's sub-steps
// (soft_stages.cpp, xpbd_stages.cpp). A colour is cut into
// kChunksPerThread chunks per thread, each thread starting on its own share
// (parallel_stages.cpp), so that a colour's blocks tend to stay on one
// thread from pass to pass while the threads still even out a colour whose
// parts cost differently; the overflow is one serial stage, in order, or
// a stage over its independent runs (overflow_runs.h).
#pragma once

#include <deque>
#include <limits>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/block_colours.h"

namespace contactsim {

class ColourStages {
 public:
  using Fn = ParallelRunner::StageFn;
  static constexpr int kChunksPerThread = 4;
  static constexpr int kSerial = std::numeric_limits<int>::max();  // one thread takes the stage whole

  // Appends to `stages` (cleared first) for a runner of `threads`.
  ColourStages(std::vector<ParallelRunner::Stage>* stages, int threads) : stages_(stages), threads_(threads) {
    stages_->clear();
  }
  // fn over [begin, end) in chunks of `grain`; an empty range adds nothing.
  // `fn` must outlive the Stages call.
  void Add(const Fn& fn, int begin, int end, int grain) {
    if (end > begin) stages_->push_back({&fn, begin, end, grain});
  }
  // fn(0, 1) on one thread.
  void AddSerial(const Fn& fn) { Add(fn, 0, 1, kSerial); }
  // fn over each colour of `blocks` blocks, then over the overflow: one
  // serial stage, or a stage over its runs (overflow_runs.h), each run
  // fn(run's begin, run's end) on one thread. `colours` must outlive the
  // Stages call, and so must this list when the overflow has runs (it
  // holds the stage's function).
  void AddColours(const Fn& fn, const BlockColours& colours, int blocks) {
    for (int c = 0; c < colours.colours(); ++c) {
      Add(fn, colours.starts[c], colours.starts[c + 1], Grain(colours.starts[c + 1] - colours.starts[c]));
    }
    const std::vector<int>& runs = colours.overflow_runs;
    if (runs.empty()) {
      Add(fn, colours.starts.back(), blocks, kSerial);
      return;
    }
    run_fns_.emplace_back([&fn, &runs](int i, int j) {
      for (int r = i; r < j; ++r) fn(runs[r], runs[r + 1]);
    });
    const int count = static_cast<int>(runs.size()) - 1;
    Add(run_fns_.back(), 0, count, Grain(count));
  }

 private:
  // kChunksPerThread chunks a thread of a stage of `size` indices
  int Grain(int size) const {
    const int chunks = kChunksPerThread * threads_;
    return (size + chunks - 1) / chunks;
  }

  std::vector<ParallelRunner::Stage>* stages_;
  int threads_;
  std::deque<Fn> run_fns_;  // the overflow runs' stage functions (stable addresses)
};

}  // namespace contactsim
