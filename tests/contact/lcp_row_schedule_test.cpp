// Tests of the sweep order of projected Gauss-Seidel (row_schedule.h).
#include "service/contact/lcp/row_schedule.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace contactsim {
namespace {

ConstraintRow RowOn(int a, int b) {
  ConstraintRow r;
  r.a = a;
  r.b = b;
  return r;
}

// Verifies that the order is a permutation that keeps every two rows
// sharing a body with mass in the caller's order (so that the sweep
// computes what the caller's order computes), on random runs between 12
// bodies of which 2 are static, some against the world (-1).
TEST(RowSchedule, KeepsTheOrderOfRowsThatShareAMovingBody) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> body(-1, 11), length(1, 12);
  std::vector<SolverBody> bodies(12);
  for (int i = 0; i < 12; ++i) bodies[i].inv_mass = i < 2 ? 0.0 : 1.0;
  auto moves = [&](int i) { return i >= 0 && bodies[i].inv_mass > 0.0; };
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<ConstraintRow> rows;
    for (int run = 0; run < 40; ++run) {
      const int a = body(rng);
      int b = body(rng);
      if (b == a) b = -1;
      for (int k = length(rng); k > 0; --k) rows.push_back(RowOn(a, b));
    }
    RowSchedule schedule;
    std::vector<int> order;
    schedule.Order(rows, bodies, &order);
    ASSERT_EQ(order.size(), rows.size());
    std::vector<int> position(rows.size(), -1);
    for (size_t k = 0; k < order.size(); ++k) {
      ASSERT_GE(order[k], 0);
      ASSERT_LT(order[k], static_cast<int>(rows.size()));
      ASSERT_EQ(position[order[k]], -1) << "row " << order[k] << " twice";
      position[order[k]] = static_cast<int>(k);
    }
    for (size_t i = 0; i < rows.size(); ++i) {
      for (size_t j = i + 1; j < rows.size(); ++j) {
        const bool share = (moves(rows[i].a) && (rows[i].a == rows[j].a || rows[i].a == rows[j].b)) ||
                           (moves(rows[i].b) && (rows[i].b == rows[j].a || rows[i].b == rows[j].b));
        if (share) {
          EXPECT_LT(position[i], position[j]) << "rows " << i << ", " << j << " trial " << trial;
        }
      }
    }
  }
}

// Verifies that runs on disjoint bodies are interleaved (row 0 of each,
// then row 1 of each) and that a run on a body of an earlier run waits for
// it; a static body (0) orders nothing.
TEST(RowSchedule, InterleavesRunsOnDisjointBodies) {
  std::vector<SolverBody> bodies(5);
  for (int i = 1; i < 5; ++i) bodies[i].inv_mass = 1.0;
  // runs: (1,2) x3, (3,4) x2, (0,3) x1 on static 0 and 3, (2,3) x2
  const std::vector<ConstraintRow> rows = {RowOn(1, 2), RowOn(1, 2), RowOn(1, 2), RowOn(3, 4),
                                           RowOn(3, 4), RowOn(0, 3), RowOn(2, 3), RowOn(2, 3)};
  RowSchedule schedule;
  std::vector<int> order;
  schedule.Order(rows, bodies, &order);
  // level 0: runs (1,2), (3,4); level 1: (0,3); level 2: (2,3)
  EXPECT_EQ(order, (std::vector<int>{0, 3, 1, 4, 2, 5, 6, 7}));
}

}  // namespace
}  // namespace contactsim
