// The stage list of a solver whose passes sweep coloured blocks
// (block_colours.h) on ParallelRunner::Stages: soft's and xpbd's sub-steps
// (soft_stages.cpp, xpbd_stages.cpp). A colour is cut into
// kChunksPerThread chunks per thread, each thread starting on its own share
// (parallel_stages.cpp), so that a colour's blocks tend to stay on one
// thread from pass to pass while the threads still even out a colour whose
// parts cost differently; the overflow is one serial stage, in order.
#pragma once

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
  // fn over each colour of `blocks` blocks, then over the overflow.
  void AddColours(const Fn& fn, const BlockColours& colours, int blocks) {
    const int chunks = kChunksPerThread * threads_;
    for (int c = 0; c < colours.colours(); ++c) {
      const int size = colours.starts[c + 1] - colours.starts[c];
      Add(fn, colours.starts[c], colours.starts[c + 1], (size + chunks - 1) / chunks);
    }
    Add(fn, colours.starts.back(), blocks, kSerial);
  }

 private:
  std::vector<ParallelRunner::Stage>* stages_;
  int threads_;
};

}  // namespace contactsim
