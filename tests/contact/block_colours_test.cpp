// Tests of ColourBlocks (block_colours.h): a colour's blocks share no
// dynamic body, the order within a colour is the given one, static bodies
// take no colour, and the overflow holds what must stay serial.
#include "service/contact/block_colours.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <vector>

namespace contactsim {
namespace {

struct Point {
  int a = 0, b = 0;
};

// One block per pair of `pairs`, each of `points_per_block` points, in
// the given order; `first` identifies a block after the reordering.
void MakeBlocks(const std::vector<std::pair<int, int>>& pairs, int points_per_block, std::vector<Point>* points,
                std::vector<NormalBlock>* blocks) {
  for (const auto& [a, b] : pairs) {
    blocks->push_back(NormalBlock{static_cast<int>(points->size()), points_per_block, false, Eigen::Matrix4d::Zero()});
    for (int i = 0; i < points_per_block; ++i) points->push_back({a, b});
  }
}

// Checks the partition: every block once, colours [starts[c], starts[c+1])
// with no shared kColoured body, and each colour and the overflow in the
// given order (the blocks' `first` rises within each).
void ExpectValidColouring(const std::vector<Point>& points, const std::vector<ColourRole>& roles,
                          const std::vector<NormalBlock>& before, const std::vector<NormalBlock>& after,
                          const BlockColours& colours) {
  ASSERT_EQ(after.size(), before.size());
  std::multiset<int> firsts_before, firsts_after;
  for (const NormalBlock& b : before) firsts_before.insert(b.first);
  for (const NormalBlock& b : after) firsts_after.insert(b.first);
  EXPECT_EQ(firsts_before, firsts_after);
  ASSERT_GE(colours.starts.size(), 1u);
  EXPECT_EQ(colours.starts.front(), 0);
  EXPECT_LE(colours.colours(), BlockColours::kMaxColours);
  std::vector<int> ends = colours.starts;
  ends.push_back(static_cast<int>(after.size()));
  for (size_t c = 0; c + 1 < ends.size(); ++c) {
    ASSERT_LE(ends[c], ends[c + 1]);
    const bool overflow = c + 1 == ends.size() - 1;
    std::set<int> bodies;
    for (int k = ends[c]; k < ends[c + 1]; ++k) {
      if (k > ends[c]) EXPECT_LT(after[k - 1].first, after[k].first) << "colour " << c << " out of order";
      if (overflow) continue;
      for (const int body : {points[after[k].first].a, points[after[k].first].b}) {
        EXPECT_NE(roles[body], ColourRole::kSerial) << "a serial body's block in colour " << c;
        if (roles[body] != ColourRole::kColoured) continue;
        EXPECT_TRUE(bodies.insert(body).second) << "body " << body << " twice in colour " << c;
      }
    }
    if (!overflow) EXPECT_GT(ends[c + 1], ends[c]) << "empty colour " << c;
  }
}

// Verifies the colouring of random contact graphs: 1 to 300 bodies, some
// static, some serial, blocks of 1 to 4 points.
TEST(BlockColoursTest, RandomGraphsColourValidly) {
  std::mt19937 rng(7);
  for (int round = 0; round < 200; ++round) {
    const int n = 1 + static_cast<int>(rng() % 300);
    std::vector<ColourRole> roles(n, ColourRole::kColoured);
    for (ColourRole& r : roles) {
      const unsigned pick = rng() % 10;
      if (pick == 0) r = ColourRole::kFixed;
      if (pick == 1 && round % 2 == 0) r = ColourRole::kSerial;
    }
    std::vector<std::pair<int, int>> pairs;
    const int m = static_cast<int>(rng() % (3 * n + 1));
    for (int k = 0; k < m; ++k) {
      const int a = static_cast<int>(rng() % n), b = static_cast<int>(rng() % n);
      if (a == b || (roles[a] == ColourRole::kFixed && roles[b] == ColourRole::kFixed)) continue;
      pairs.emplace_back(a, b);
    }
    std::vector<Point> points;
    std::vector<NormalBlock> blocks;
    MakeBlocks(pairs, 1 + static_cast<int>(rng() % 4), &points, &blocks);
    const std::vector<NormalBlock> before = blocks;
    const BlockColours colours = ColourBlocks(points, roles, &blocks);
    ExpectValidColouring(points, roles, before, blocks, colours);
  }
}

// Verifies the degenerate cases: no blocks; every block on the ground
// (static: one colour for all); a chain (two colours, alternating from the
// first); a body in 40 pairs (32 colours, then 8 in the overflow, in order).
TEST(BlockColoursTest, DegenerateGraphs) {
  std::vector<Point> points;
  std::vector<NormalBlock> blocks;
  BlockColours colours = ColourBlocks(points, std::vector<ColourRole>{}, &blocks);
  EXPECT_EQ(colours.colours(), 0);
  EXPECT_EQ(colours.starts, std::vector<int>{0});

  std::vector<ColourRole> roles(41, ColourRole::kColoured);
  roles[0] = ColourRole::kFixed;
  std::vector<std::pair<int, int>> on_ground;
  for (int i = 1; i <= 40; ++i) on_ground.emplace_back(0, i);
  MakeBlocks(on_ground, 4, &points, &blocks);
  colours = ColourBlocks(points, roles, &blocks);
  EXPECT_EQ(colours.starts, (std::vector<int>{0, 40}));

  points.clear(), blocks.clear();
  std::vector<std::pair<int, int>> chain;
  for (int i = 1; i < 40; ++i) chain.emplace_back(i, i + 1);
  MakeBlocks(chain, 1, &points, &blocks);
  std::vector<NormalBlock> before = blocks;
  colours = ColourBlocks(points, roles, &blocks);
  EXPECT_EQ(colours.starts, (std::vector<int>{0, 20, 39}));
  ExpectValidColouring(points, roles, before, blocks, colours);

  points.clear(), blocks.clear();
  std::vector<std::pair<int, int>> star;
  for (int i = 2; i <= 40; ++i) star.emplace_back(1, i);
  star.emplace_back(2, 3);
  MakeBlocks(star, 2, &points, &blocks);
  before = blocks;
  colours = ColourBlocks(points, roles, &blocks);
  EXPECT_EQ(colours.colours(), BlockColours::kMaxColours);
  EXPECT_EQ(static_cast<int>(blocks.size()) - colours.starts.back(), 7);  // 39 - 32 of the star
  ExpectValidColouring(points, roles, before, blocks, colours);
}

// Verifies that a serial body's blocks all go to the overflow in their
// given order, and that the others colour as without it.
TEST(BlockColoursTest, SerialBodiesKeepTheirOrderInTheOverflow) {
  std::vector<ColourRole> roles(6, ColourRole::kColoured);
  roles[0] = ColourRole::kFixed;
  roles[3] = ColourRole::kSerial;
  std::vector<Point> points;
  std::vector<NormalBlock> blocks;
  MakeBlocks({{3, 4}, {1, 2}, {0, 3}, {2, 5}, {0, 1}, {4, 3}}, 1, &points, &blocks);
  const std::vector<NormalBlock> before = blocks;
  const BlockColours colours = ColourBlocks(points, roles, &blocks);
  ExpectValidColouring(points, roles, before, blocks, colours);
  ASSERT_EQ(colours.starts.back(), 3);
  EXPECT_EQ(blocks[3].first, 0);  // (3, 4)
  EXPECT_EQ(blocks[4].first, 2);  // (0, 3)
  EXPECT_EQ(blocks[5].first, 5);  // (4, 3)
}

}  // namespace
}  // namespace contactsim
