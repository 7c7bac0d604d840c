// Tests of CollisionDetector: the thread count is checked, and any number
// of threads gives the serial detector's pairs, contacts and separating-axis
// cache, bit for bit, step after step; the collision filter drops exactly
// the pairs ShouldCollide refuses, under either broadphase.
#include "service/collision/collision_detector.h"

#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cstring>
#include <random>

#include "service/physics/collision_filter.h"
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

// Gives the heap's bodies random filters (a third keep the default) and
// joins random pairs, half of them allowed to touch.
void RandomFilters(World* world, std::mt19937_64* rng) {
  std::uniform_int_distribution<int> pick(0, 5), group(-2, 2), bit(0, 3);
  auto& bodies = world->bodies();
  for (size_t i = 1; i < bodies.size(); ++i) {
    if (pick(*rng) < 2) continue;
    const uint32_t category = 1u << bit(*rng);
    const uint32_t mask = ~(1u << bit(*rng));
    ASSERT_TRUE(world->SetCollisionFilter(bodies[i].id, category, mask, group(*rng)).ok());
  }
  std::uniform_int_distribution<size_t> body(1, bodies.size() - 1);
  for (int k = 0; k < 40; ++k) {
    JointSettings s;
    s.body_a = bodies[body(*rng)].id;
    s.body_b = bodies[body(*rng)].id;
    if (s.body_a == s.body_b) continue;
    s.anchor = world->Find(s.body_a)->x;
    s.collide_connected = k % 2 == 0;
    JointId id = 0;
    ASSERT_TRUE(world->AddJoint(s, &id).ok());
  }
}

// Verifies that sweep and prune and the naive broadphase give the same
// filtered pairs and contacts, and that these are exactly the unfiltered
// heap's pairs that ShouldCollide accepts (the filter drops nothing else
// and keeps nothing it refuses).
TEST(CollisionDetectorTest, FilterDropsExactlyTheRefusedPairsUnderEitherBroadphase) {
  constexpr double kMargin = 0.01, kDt = 1.0 / 240.0;
  for (const uint64_t seed : {3u, 17u, 29u}) {
    World world = Heap(300, seed);
    std::mt19937_64 rng(seed);
    RandomFilters(&world, &rng);
    World plain = world;  // the same poses, no filters, no joints
    for (RigidBody& b : plain.bodies()) ASSERT_TRUE(plain.SetCollisionFilter(b.id, 1u, 0xFFFFFFFFu, 0).ok());
    ASSERT_TRUE(plain.AssignJoints({}, plain.next_joint_id).ok());
    CollisionDetector sap, naive, reference;
    ASSERT_TRUE(naive.SetBroadphase("naive").ok());
    ContactSet from_sap, from_naive, unfiltered;
    sap.Detect(world, kMargin, kDt, &from_sap);
    naive.Detect(world, kMargin, kDt, &from_naive);
    reference.Detect(plain, kMargin, kDt, &unfiltered);
    ASSERT_EQ(sap.pairs(), naive.pairs());
    ExpectBitIdentical(from_sap, from_naive);
    std::vector<BodyPair> accepted;
    const auto& bodies = world.bodies();
    for (const BodyPair& p : reference.pairs()) {
      if (ShouldCollide(bodies[p.first], bodies[p.second], world.joined_pairs())) accepted.push_back(p);
    }
    EXPECT_EQ(sap.pairs(), accepted);
    EXPECT_LT(accepted.size(), reference.pairs().size()) << "the filters should refuse some pairs";
    EXPECT_GT(accepted.size(), reference.pairs().size() / 4) << "and accept others";
    for (const Contact& c : from_sap) {
      ASSERT_TRUE(ShouldCollide(bodies[c.a], bodies[c.b], world.joined_pairs())) << c.a << " " << c.b;
    }
  }
}

}  // namespace
}  // namespace contactsim
