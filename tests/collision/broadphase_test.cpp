#include "service/collision/broadphase.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <random>

#include "service/collision/naive_broadphase.h"
#include "service/collision/sweep_and_prune.h"

namespace contactsim {
namespace {

// A random scene: n boxes of size up to `size` in a cube whose side makes the
// expected number of overlaps per box about `density`; one in five static.
struct Scene {
  std::vector<Aabb> boxes;
  std::vector<bool> movable;
};

constexpr double kBoxSize = 1.0;  // m, largest box side

// Side of the scene cube: two boxes of mean side s = 0.55 kBoxSize overlap
// when their centres are within s on all three axes, with probability
// (2 s / L)^3 = density / n for L = 2 s (n / density)^(1/3); about
// n density / 2 pairs in all.
double SceneSide(int n, double density) { return 2.0 * 0.55 * kBoxSize * std::cbrt(n / density); }

Scene RandomScene(int n, double density, std::mt19937* rng) {
  const double size = kBoxSize;
  const double side = SceneSide(n, density);
  std::uniform_real_distribution<double> pos(0.0, side), ext(0.1 * size, size);
  std::bernoulli_distribution is_static(0.2);
  Scene scene;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(pos(*rng), pos(*rng), pos(*rng));
    const Vec3 h(0.5 * ext(*rng), 0.5 * ext(*rng), 0.5 * ext(*rng));
    scene.boxes.push_back({c - h, c + h});
    scene.movable.push_back(!is_static(*rng));
  }
  return scene;
}

void Move(Scene* scene, double step, std::mt19937* rng) {
  std::uniform_real_distribution<double> d(-step, step);
  for (std::size_t i = 0; i < scene->boxes.size(); ++i) {
    if (!scene->movable[i]) continue;
    const Vec3 v(d(*rng), d(*rng), d(*rng));
    scene->boxes[i].min += v;
    scene->boxes[i].max += v;
  }
}

std::vector<BodyPair> Pairs(Broadphase* broadphase, const Scene& scene) {
  std::vector<BodyPair> pairs = {{-1, -1}};  // must be cleared
  broadphase->FindPairs(scene.boxes, scene.movable, &pairs);
  return pairs;
}

void ExpectSortedAndOrdered(const std::vector<BodyPair>& pairs) {
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    ASSERT_LT(pairs[i].first, pairs[i].second);
    if (i > 0) {
      ASSERT_LT(pairs[i - 1], pairs[i]);
    }
  }
}

// Verifies the factory makes both broadphases and names the known ones when
// the name is wrong.
TEST(BroadphaseTest, FactoryKnowsNaiveAndSapAndRejectsOthers) {
  std::unique_ptr<Broadphase> bp;
  ASSERT_TRUE(CreateBroadphase("naive", &bp).ok());
  EXPECT_STREQ(bp->Name(), "naive");
  ASSERT_TRUE(CreateBroadphase("sap", &bp).ok());
  EXPECT_STREQ(bp->Name(), "sap");
  const Status s = CreateBroadphase("octree", &bp);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "unknown broadphase \"octree\"; known: naive, sap");
}

// Verifies touching boxes count as overlapping and two static boxes are
// never a pair, in both broadphases.
TEST(BroadphaseTest, TouchingCountsAndStaticPairsAreSkipped) {
  Scene scene;
  scene.boxes = {{Vec3(0, 0, 0), Vec3(1, 1, 1)}, {Vec3(1, 0, 0), Vec3(2, 1, 1)},
                 {Vec3(0.5, 0.5, 0.5), Vec3(1.5, 1.5, 1.5)}, {Vec3(5, 5, 5), Vec3(6, 6, 6)}};
  scene.movable = {false, false, true, true};
  const std::vector<BodyPair> expected = {{0, 2}, {1, 2}};
  NaiveBroadphase naive;
  SweepAndPrune sap;
  EXPECT_EQ(Pairs(&naive, scene), expected);
  EXPECT_EQ(Pairs(&sap, scene), expected);
}

// Verifies naive and sap give the same sorted pairs on random scenes of many
// sizes and densities.
TEST(BroadphaseTest, SapMatchesNaiveOnRandomScenes) {
  std::mt19937 rng(1);
  for (int n : {10, 50, 200, 1000, 2000}) {
    for (double density : {0.1, 1.0, 8.0}) {
      const Scene scene = RandomScene(n, density, &rng);
      NaiveBroadphase naive;
      SweepAndPrune sap;
      const std::vector<BodyPair> expected = Pairs(&naive, scene);
      EXPECT_EQ(Pairs(&sap, scene), expected) << "n " << n << " density " << density;
      ExpectSortedAndOrdered(expected);
      // the scenes are not trivially empty: about n density / 2 pairs
      if (density >= 1.0 && n >= 200) {
        EXPECT_GT(expected.size(), static_cast<std::size_t>(n * density / 8));
      }
    }
  }
}

// Verifies the incremental repair across steps of motion: same pairs as
// naive, no rebuild while the body count holds, and few swaps per step.
TEST(BroadphaseTest, SapRepairsIncrementallyAcrossSteps) {
  std::mt19937 rng(2);
  for (int n : {10, 300, 2000}) {
    const double density = 2.0, step = 0.05;
    Scene scene = RandomScene(n, density, &rng);
    // a box moving by up to `step` passes the boxes that start within `step`
    // of it on the axis: n / side of them per metre. A full re-sort by
    // insertion would cost ~n^2 / 4 swaps.
    const double swap_bound = n * (n / SceneSide(n, density)) * step + n;
    NaiveBroadphase naive;
    SweepAndPrune sap;
    Pairs(&sap, scene);
    EXPECT_TRUE(sap.last_rebuilt());
    for (int k = 0; k < 20; ++k) {
      Move(&scene, step, &rng);
      EXPECT_EQ(Pairs(&sap, scene), Pairs(&naive, scene)) << "n " << n << " step " << k;
      EXPECT_FALSE(sap.last_rebuilt());
      EXPECT_LT(sap.last_swaps(), swap_bound);
    }
    // large motion: still correct, at the cost of more swaps
    Move(&scene, 5.0, &rng);
    EXPECT_EQ(Pairs(&sap, scene), Pairs(&naive, scene));
  }
}

// Verifies adding and removing boxes (with and without Reset) keeps the pair
// sets equal.
TEST(BroadphaseTest, SapHandlesAddedAndRemovedBoxes) {
  std::mt19937 rng(3);
  Scene scene = RandomScene(500, 2.0, &rng);
  NaiveBroadphase naive;
  SweepAndPrune sap;
  for (int round = 0; round < 10; ++round) {
    Move(&scene, 0.1, &rng);
    if (round % 3 == 0) {
      const Scene extra = RandomScene(37, 2.0, &rng);
      scene.boxes.insert(scene.boxes.end(), extra.boxes.begin(), extra.boxes.end());
      scene.movable.insert(scene.movable.end(), extra.movable.begin(), extra.movable.end());
    } else if (round % 3 == 1) {
      scene.boxes.erase(scene.boxes.begin() + 10, scene.boxes.begin() + 60);
      scene.movable.erase(scene.movable.begin() + 10, scene.movable.begin() + 60);
      sap.Reset();
    } else {
      // same count, different bodies (a removal and an addition without a Reset)
      const Scene one = RandomScene(1, 2.0, &rng);
      scene.boxes[round] = one.boxes[0];
    }
    EXPECT_EQ(Pairs(&sap, scene), Pairs(&naive, scene)) << "round " << round;
  }
}

// Verifies a ground plane (a huge box, as aabb.cpp makes) pairs with every
// movable box and does not drag the sweep axis onto its own normal.
TEST(BroadphaseTest, PlaneBoxPairsWithEveryMovableBox) {
  std::mt19937 rng(4);
  Scene scene = RandomScene(300, 1.0, &rng);
  for (Aabb& box : scene.boxes) {  // a scene spread along x
    box.min.x() *= 20.0;
    box.max.x() = box.min.x() + 0.5;
  }
  scene.boxes.push_back({Vec3::Constant(-1e15), Vec3(1e15, 1e15, 1e3)});
  scene.movable.push_back(false);
  NaiveBroadphase naive;
  SweepAndPrune sap;
  const std::vector<BodyPair> pairs = Pairs(&sap, scene);
  EXPECT_EQ(pairs, Pairs(&naive, scene));
  EXPECT_EQ(sap.axis(), 0);
  int with_plane = 0, movable = 0;
  for (const BodyPair& p : pairs) with_plane += p.second == 300;
  for (int i = 0; i < 300; ++i) movable += scene.movable[i];
  EXPECT_EQ(with_plane, movable);
}

// Verifies that sweep and prune on 2 and 4 threads finds exactly the naive
// pairs, sorted, over moving scenes from empty to 3,000 boxes, sparse and
// dense (the threads' own lists are merged by the sort).
TEST(BroadphaseTest, SweepOnThreadsMatchesNaive) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  std::mt19937 rng(11);
  for (const int threads : {2, 4}) {
    ParallelRunner runner(threads);
    for (const int n : {0, 1, 2, 129, 1000, 3000}) {
      for (const double density : {0.5, 8.0}) {
        Scene scene = RandomScene(n, density, &rng);
        NaiveBroadphase naive;
        SweepAndPrune sap;
        sap.SetRunner(&runner);
        for (int step = 0; step < 3; ++step) {
          const std::vector<BodyPair> got = Pairs(&sap, scene);
          ExpectSortedAndOrdered(got);
          EXPECT_EQ(got, Pairs(&naive, scene)) << threads << " threads, n " << n << ", density " << density;
          Move(&scene, 0.2 * kBoxSize, &rng);
        }
      }
    }
  }
}

}  // namespace
}  // namespace contactsim
