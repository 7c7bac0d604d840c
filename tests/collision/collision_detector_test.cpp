// Tests of CollisionDetector: the thread count is checked, and any number
// of threads gives the serial detector's pairs, contacts and separating-axis
// cache, bit for bit, step after step.
#include "service/collision/collision_detector.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cstring>
#include <random>

#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::RandomRotation;
using testing_util::RandomVector;

// A heap of boxes, rock hulls, spheres and capsules over a ground plane,
// packed so that a few hundred pairs touch and many more are near.
World Heap(int bodies, uint64_t seed) {
  std::mt19937_64 rng(seed);
  World world;
  world.AddBody(testing_util::Ground(0));
  const auto rock = testing_util::RockHull();
  for (int i = 0; i < bodies; ++i) {
    const Vec3 x = RandomVector(rng, 1.5) + Vec3(0, 0, 1.6);
    const Quat q = RandomRotation(rng);
    RigidBody body;
    switch (i % 4) {
      case 0: body = testing_util::Box(0, Vec3(0.2, 0.15, 0.1), x, q); break;
      case 1: body = testing_util::Convex(0, rock, x, q); break;
      case 2: body = testing_util::Sphere(0, 0.15, x); break;
      default: body = testing_util::Capsule(0, 0.08, 0.15, x, q); break;
    }
    world.AddBody(body);
  }
  return world;
}

// Moves every body a little, as a step would, so that cached axes are hit,
// missed, stored and erased.
void Jiggle(World* world, std::mt19937_64* rng) {
  for (RigidBody& body : world->bodies()) {
    if (body.shape.type == ShapeType::kPlane) continue;
    body.x += RandomVector(*rng, 0.01);
    body.q = (body.q * Quat(Eigen::AngleAxisd(0.02, RandomVector(*rng, 1.0).normalized()))).normalized();
  }
}

void ExpectBitIdentical(const ContactSet& x, const ContactSet& y) {
  ASSERT_EQ(x.size(), y.size());
  for (size_t k = 0; k < x.size(); ++k) {
    EXPECT_EQ(x[k].a, y[k].a) << k;
    EXPECT_EQ(x[k].b, y[k].b) << k;
    EXPECT_EQ(x[k].feature_id, y[k].feature_id) << k;
    EXPECT_EQ(std::memcmp(x[k].point.data(), y[k].point.data(), sizeof(double) * 3), 0) << k;
    EXPECT_EQ(std::memcmp(x[k].normal.data(), y[k].normal.data(), sizeof(double) * 3), 0) << k;
    EXPECT_EQ(std::memcmp(&x[k].depth, &y[k].depth, sizeof(double)), 0) << k;
  }
}

// Verifies that SetThreads refuses counts outside 1..kMaxThreads, naming
// the value, and keeps the previous count.
TEST(CollisionDetectorTest, SetThreadsRefusesBadCounts) {
  CollisionDetector detector;
  EXPECT_EQ(detector.threads(), 1);
  ASSERT_TRUE(detector.SetThreads(2).ok());
  const Status st = detector.SetThreads(0);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(st.message(), "threads must be between 1 and 256, got 0");
  EXPECT_EQ(detector.threads(), 2);
}

// Verifies that 2, 3 and 4 threads give the serial detector's candidate
// pairs, contacts (in the same order, bit for bit) and cache counters over
// steps on which cached axes are hit, missed, stored and erased.
TEST(CollisionDetectorTest, AnyThreadCountGivesTheSerialResult) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  constexpr double kMargin = 0.01;  // m, as the impulse method's speculative band
  constexpr double kDt = 1.0 / 240.0;
  for (const int threads : {2, 3, 4}) {
    World world = Heap(600, 11);
    CollisionDetector serial, parallel;
    ASSERT_TRUE(parallel.SetThreads(threads).ok());
    std::mt19937_64 rng(5);
    int touching_steps = 0;
    for (int step = 0; step < 8; ++step) {
      ContactSet expected, got;
      serial.Detect(world, kMargin, kDt, &expected);
      parallel.Detect(world, kMargin, kDt, &got);
      ASSERT_EQ(serial.pairs(), parallel.pairs());
      ExpectBitIdentical(expected, got);
      const SeparatingAxisCache& a = serial.narrowphase().cache();
      const SeparatingAxisCache& b = parallel.narrowphase().cache();
      EXPECT_EQ(a.hits(), b.hits());
      EXPECT_EQ(a.misses(), b.misses());
      EXPECT_EQ(a.size(), b.size());
      touching_steps += expected.size() > 100;
      Jiggle(&world, &rng);
    }
    EXPECT_EQ(touching_steps, 8) << "the heap should stay in contact";
    EXPECT_GT(serial.narrowphase().cache().hits(), 0);
    EXPECT_GT(serial.stats().candidate_pairs, 500);
  }
}

}  // namespace
}  // namespace contactsim
