// The order in which projected Gauss-Seidel visits constraint rows: the
// caller's order, rearranged so that consecutive rows touch different
// bodies, with the same result bit for bit.
//
// A row's update reads and writes the velocities of its two bodies, so
// rows in contact order (a box pair's manifold is ~12 rows on the same two
// bodies) form one serial chain: each update waits for the last one's
// store. Two updates that share no body with mass commute, so any order
// that keeps every pair of rows sharing such a body in the caller's order
// computes the same sweep (the same operations on each body's velocity, in
// the same order). The rows are grouped into runs (consecutive rows on the
// same body pair: a contact manifold's normal and friction rows, a joint's
// block) and each run gets a level, one more than the highest level of an
// earlier run on one of its bodies (a wavefront, as in level scheduling of
// sparse triangular solves, Anderson and Saad 1989); runs of one level
// share no body, so the sweep takes the levels in turn and, within a
// level, interleaves its runs: row 0 of every run, then row 1 of every
// run, ... Static and kinematic bodies take no impulse and do not order
// anything.
//
// Colour (the solve of the lcp method's pgs, on the world's threads): the
// runs are coloured instead (block_colours.h: greedy, each run takes the
// lowest colour neither of its moving bodies has yet), so that runs of one
// colour share no moving body and may be swept by any thread in any order
// with the same result bit for bit (docs/architecture.md, "Threads"). A
// colour's runs are cut into groups of kRunsPerGroup, interleaved as above
// within a group; the group is the unit a thread takes. Colours are fewer
// than levels, but the sweep is no longer the caller's order: a coloured
// Gauss-Seidel sweep, the same one on any number of threads. The runs of
// rows the caller marks as ordered (a joint's) and every run on one of
// their bodies keep the caller's order instead: they are the overflow, one
// group after the colours, in levels as above. Coloured alternately, the
// rows of a 100-link chain of growing masses converged too slowly in 20
// sweeps to hold it together.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/block_colours.h"
#include "service/contact/constraint_row.h"

namespace contactsim {

class RowSchedule {
 public:
  // Fills *order with a permutation of the rows' indices: the sweep order.
  // `bodies` tells which bodies take impulses (inv_mass > 0).
  void Order(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
             std::vector<int>* order);

  // Runs interleaved within a group: enough independent updates to overlap
  // in the CPU, few enough that a colour splits evenly between threads.
  static constexpr int kRunsPerGroup = 8;
  // The coloured order: *order as above; group g's rows are
  // order[group_rows[g], group_rows[g + 1]); `colours` in groups (a
  // colour's groups share no moving body; the overflow, at most one group,
  // keeps the caller's order). Rows from `first_ordered` on are ordered.
  // With a runner, the groups' rows are written on its threads (each group
  // its own slots: the same order on any thread count).
  void Colour(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies, int first_ordered,
              std::vector<int>* order, std::vector<int>* group_rows, BlockColours* colours,
              ParallelRunner* runner = nullptr);

 private:
  struct Run {
    int first, count, level;
  };
  struct Ends {
    int a, b;  // bodies, the world as bodies.size()
    bool operator==(const Ends& o) const { return a == o.a && b == o.b; }
  };
  // Colour's order from ends_ and roles_ (made from the same rows and
  // bodies), when they differ from the last call's.
  void ColourAnew(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                  std::vector<int>* order, std::vector<int>* group_rows, BlockColours* colours,
                  ParallelRunner* runner);
  // groups a thread fills at a time (a group is a few dozen rows), and
  // rows whose bodies it reads at a time
  static constexpr int kFillGrain = 64;
  static constexpr int kEndsGrain = 2048;
  // runs_ from the rows: consecutive rows on the same body pair
  void FindRuns(const std::vector<ConstraintRow>& rows);
  // Appends row s of every run in sorted_[begin, end) for s = 0, 1, ...
  void Interleave(int begin, int end, std::vector<int>* order) const;
  // The same written from `out` on; returns the end of what it wrote.
  int* Interleave(int begin, int end, int* out) const;
  // Appends the rows of sorted_[begin, end) (runs in the caller's order)
  // level by level, each level interleaved.
  void AppendByLevel(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies, int begin,
                     int end, std::vector<int>* order);
  std::vector<int> body_level_;  // per body: level of the last run on it
  std::vector<Run> runs_;
  std::vector<int> level_start_, cursor_;
  std::vector<Ends> ends_;             // per row
  std::vector<ColourRole> roles_;      // per body, and the world
  std::vector<NormalBlock> coloured_;  // the runs as blocks of rows, colour by colour
  std::vector<Run> sorted_;            // the runs in sweep order
  std::vector<Run> level_sorted_;
  std::vector<int> group_first_run_;  // per coloured group: its first run in sorted_, then the overflow's
  // the last coloured call's rows' bodies and bodies' roles, and its answer
  std::vector<Ends> last_ends_;
  std::vector<ColourRole> last_roles_;
  std::vector<int> last_order_, last_group_rows_;
  BlockColours last_colours_;
};

}  // namespace contactsim
