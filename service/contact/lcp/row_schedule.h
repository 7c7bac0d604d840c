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
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"

namespace contactsim {

class RowSchedule {
 public:
  // Fills *order with a permutation of the rows' indices: the sweep order.
  // `bodies` tells which bodies take impulses (inv_mass > 0).
  void Order(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
             std::vector<int>* order);

 private:
  struct Run {
    int first, count, level;
  };
  std::vector<int> body_level_;  // per body: level of the last run on it
  std::vector<Run> runs_;
  std::vector<int> by_level_;    // run indices grouped by level, row order within a level
  std::vector<int> level_start_, cursor_;
};

}  // namespace contactsim
