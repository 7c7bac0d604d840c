// Tests of SplitOverflow (overflow_runs.h): the overflow's blocks split
// into runs that share no movable body, each run in the given order, the
// colours before them untouched; and a sweep of the runs on the threads
// (ColourStages) writes what one sweep in the given order writes.
#include "service/contact/overflow_runs.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "service/contact/colour_stages.h"

namespace contactsim {
namespace {

struct Point {
  int a = 0, b = 0;
};

// A random overflow of `m` blocks of one point on `n` bodies, some fixed.
void RandomOverflow(std::mt19937* rng, int n, int m, std::vector<Point>* points, std::vector<ColourRole>* roles,
                    std::vector<NormalBlock>* blocks) {
  roles->assign(n, ColourRole::kColoured);
  for (ColourRole& r : *roles) {
    if ((*rng)() % 8 == 0) r = ColourRole::kFixed;
    if ((*rng)() % 8 == 1) r = ColourRole::kSerial;
  }
  for (int k = 0; k < m; ++k) {
    const int a = static_cast<int>((*rng)() % n), b = static_cast<int>((*rng)() % n);
    if (a == b) continue;
    blocks->push_back(NormalBlock{static_cast<int>(points->size()), 1, false, Eigen::Matrix4d::Zero()});
    points->push_back({a, b});
  }
}

// Verifies on random overflows (sparse: many runs; dense: one) that the
// runs cover the overflow, keep the given order within a run, and share no
// movable body; a fixed body may be in several.
TEST(OverflowRunsTest, RunsShareNoMovableBodyAndKeepTheirOrder) {
  std::mt19937 rng(11);
  for (int round = 0; round < 100; ++round) {
    const int n = 2 + static_cast<int>(rng() % 200);
    std::vector<Point> points;
    std::vector<ColourRole> roles;
    std::vector<NormalBlock> blocks;
    RandomOverflow(&rng, n, static_cast<int>(rng() % (round % 2 == 0 ? n / 2 + 1 : 3 * n)), &points, &roles,
                   &blocks);
    BlockColours colours;
    colours.starts = {0};  // every block in the overflow
    const std::vector<NormalBlock> before = blocks;
    SplitOverflow(points, roles, &colours, &blocks);
    ASSERT_EQ(blocks.size(), before.size());
    const std::vector<int>& runs = colours.overflow_runs;
    if (runs.empty()) continue;  // one run: the overflow as it was
    ASSERT_GE(runs.size(), 3u);
    EXPECT_EQ(runs.front(), 0);
    EXPECT_EQ(runs.back(), static_cast<int>(blocks.size()));
    std::map<int, int> run_of_body;
    for (size_t r = 0; r + 1 < runs.size(); ++r) {
      ASSERT_LT(runs[r], runs[r + 1]) << "empty run " << r;
      for (int k = runs[r]; k < runs[r + 1]; ++k) {
        if (k > runs[r]) EXPECT_LT(blocks[k - 1].first, blocks[k].first) << "run " << r << " out of order";
        for (const int body : {points[blocks[k].first].a, points[blocks[k].first].b}) {
          if (roles[body] == ColourRole::kFixed) continue;
          const auto [it, fresh] = run_of_body.emplace(body, static_cast<int>(r));
          EXPECT_EQ(it->second, static_cast<int>(r)) << "body " << body << " in runs " << it->second << ", " << r;
        }
      }
    }
  }
}

// Verifies that a Gauss-Seidel-like sweep of the runs (each block reads
// its bodies' values and writes both, fixed bodies read only) on 1, 2 and
// 4 threads writes what one serial sweep in the given order writes, bit
// for bit.
TEST(OverflowRunsTest, RunsOnThreadsSweepAsOneSerialSweep) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  std::mt19937 rng(5);
  const int n = 400;
  std::vector<Point> points;
  std::vector<ColourRole> roles;
  std::vector<NormalBlock> blocks;
  RandomOverflow(&rng, n, 300, &points, &roles, &blocks);
  std::vector<double> start(n);
  for (double& v : start) v = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  const auto update = [&](const NormalBlock& m, std::vector<double>& v) {
    const Point& p = points[m.first];
    const double mean = 0.5 * (v[p.a] + v[p.b]) + 0.1 * std::sin(v[p.a] - v[p.b]);
    if (roles[p.a] != ColourRole::kFixed) v[p.a] = 0.7 * mean + 0.3 * v[p.a];
    if (roles[p.b] != ColourRole::kFixed) v[p.b] = 0.7 * mean - 0.3 * v[p.b];
  };
  std::vector<double> expected = start;
  for (int pass = 0; pass < 3; ++pass) {
    for (const NormalBlock& m : blocks) update(m, expected);
  }
  BlockColours colours;
  colours.starts = {0};
  SplitOverflow(points, roles, &colours, &blocks);
  ASSERT_GT(colours.overflow_runs.size(), 3u) << "the random overflow should split";
  for (const int threads : {1, 2, 4}) {
    ParallelRunner runner(threads);
    std::vector<double> values = start;
    const ParallelRunner::StageFn sweep = [&](int i, int j) {
      for (int k = i; k < j; ++k) update(blocks[k], values);
    };
    std::vector<ParallelRunner::Stage> stages;
    ColourStages list(&stages, threads);
    for (int pass = 0; pass < 3; ++pass) list.AddColours(sweep, colours, static_cast<int>(blocks.size()));
    runner.Stages(stages);
    EXPECT_EQ(values, expected) << threads << " threads";
  }
}

}  // namespace
}  // namespace contactsim
