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

namespace contactsim {
namespace {

// Verifies the coloured order on random runs between 40 bodies, 4 of them
// static, some against the world: a permutation; each group holds whole
// runs, their rows in the caller's order; two groups of one colour share no
// moving body; the groups of the colours come first, the overflow after.
TEST(RowSchedule, ColoursRunsSoThatAColourSharesNoMovingBody) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> body(-1, 39), length(1, 12);
  std::vector<SolverBody> bodies(40);
  for (int i = 0; i < 40; ++i) bodies[i].inv_mass = i < 4 ? 0.0 : 1.0;
  auto moves = [&](int i) { return i >= 0 && bodies[i].inv_mass > 0.0; };
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<ConstraintRow> rows;
    for (int run = 0; run < 150; ++run) {
      const int a = body(rng);
      int b = body(rng);
      if (b == a) b = -1;
      for (int k = length(rng); k > 0; --k) rows.push_back(RowOn(a, b));
    }
    RowSchedule schedule;
    std::vector<int> order, group_rows;
    BlockColours colours;
    schedule.Colour(rows, bodies, static_cast<int>(rows.size()), &order, &group_rows, &colours);
    ASSERT_EQ(order.size(), rows.size());
    ASSERT_EQ(group_rows.back(), static_cast<int>(rows.size()));
    std::vector<int> seen(rows.size(), 0);
    for (int k : order) ++seen[k];
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(rows.size())) << "trial " << trial;
    const int groups = static_cast<int>(group_rows.size()) - 1;
    ASSERT_GT(colours.colours(), 1);
    EXPECT_LE(colours.starts.back(), groups);
    std::vector<int> group_of(rows.size());
    for (int g = 0; g < groups; ++g) {
      for (int k = group_rows[g]; k < group_rows[g + 1]; ++k) group_of[order[k]] = g;
      // within a group, the rows on one pair with a moving body keep their order
      for (int k = group_rows[g] + 1; k < group_rows[g + 1]; ++k) {
        for (int l = group_rows[g]; l < k; ++l) {
          const ConstraintRow &x = rows[order[l]], &y = rows[order[k]];
          if (x.a == y.a && x.b == y.b && (moves(x.a) || moves(x.b))) {
            EXPECT_LT(order[l], order[k]);
          }
        }
      }
    }
    for (size_t i = 1; i < rows.size(); ++i) {  // a run is never cut
      if (rows[i].a == rows[i - 1].a && rows[i].b == rows[i - 1].b) {
        EXPECT_EQ(group_of[i], group_of[i - 1]);
      }
    }
    for (int c = 0; c < colours.colours(); ++c) {
      std::vector<int> owner(bodies.size(), -1);  // per body: the colour's group on it
      for (int g = colours.starts[c]; g < colours.starts[c + 1]; ++g) {
        for (int k = group_rows[g]; k < group_rows[g + 1]; ++k) {
          for (int end : {rows[order[k]].a, rows[order[k]].b}) {
            if (!moves(end)) continue;
            EXPECT_TRUE(owner[end] == -1 || owner[end] == g) << "colour " << c << " body " << end;
            owner[end] = g;
          }
        }
      }
    }
  }
}

// Verifies the overflow: a body with more pairs than there are colours
// (40 runs on body 1) keeps its last 40 - 32 runs in one group after the
// colours, in the caller's order.
TEST(RowSchedule, RunsBeyondTheLastColourAreSweptInOrderAfterTheColours) {
  std::vector<SolverBody> bodies(42);
  for (SolverBody& b : bodies) b.inv_mass = 1.0;
  std::vector<ConstraintRow> rows;
  for (int other = 2; other < 42; ++other) {
    rows.push_back(RowOn(1, other));
    rows.push_back(RowOn(1, other));
  }
  RowSchedule schedule;
  std::vector<int> order, group_rows;
  BlockColours colours;
  schedule.Colour(rows, bodies, static_cast<int>(rows.size()), &order, &group_rows, &colours);
  ASSERT_EQ(colours.colours(), BlockColours::kMaxColours);
  const int overflow = colours.starts.back();
  ASSERT_EQ(static_cast<int>(group_rows.size()) - 1, overflow + 1);
  const std::vector<int> tail(order.begin() + group_rows[overflow], order.end());
  std::vector<int> expected;
  for (int k = 2 * BlockColours::kMaxColours; k < static_cast<int>(rows.size()); ++k) expected.push_back(k);
  EXPECT_EQ(tail, expected);
}

// Verifies the ordered rows: joint rows (from index 6 on: bodies 2-3 and
// 3-world) and the contact run on body 2 go to the overflow, level by level
// (runs on disjoint bodies interleaved) in the caller's order; the contact
// runs on other bodies are coloured.
TEST(RowSchedule, OrderedRowsAndTheRowsOnTheirBodiesKeepTheCallersOrder) {
  std::vector<SolverBody> bodies(6);
  for (SolverBody& b : bodies) b.inv_mass = 1.0;
  // contacts: (4,5) x2, (1,2) x2, (0,1) x2; joints: (2,3) x2, (-1,3) x1
  const std::vector<ConstraintRow> rows = {RowOn(4, 5), RowOn(4, 5), RowOn(1, 2), RowOn(1, 2), RowOn(0, 1),
                                           RowOn(0, 1), RowOn(2, 3), RowOn(2, 3), RowOn(-1, 3)};
  RowSchedule schedule;
  std::vector<int> order, group_rows;
  BlockColours colours;
  schedule.Colour(rows, bodies, 6, &order, &group_rows, &colours);
  // colour 0: (4,5), (0,1) interleaved; overflow: (1,2), then (2,3), then (-1,3)
  ASSERT_EQ(colours.colours(), 1);
  EXPECT_EQ(order, (std::vector<int>{0, 4, 1, 5, 2, 3, 6, 7, 8}));
  EXPECT_EQ(group_rows, (std::vector<int>{0, 4, 9}));
}

}  // namespace
}  // namespace contactsim
