// Tests of the impulse method's passes colour by colour on the collision
// detector's threads (impulse_stages.cpp): the same state bit for bit on
// any number of threads, with jointed bodies (whose contacts keep their
// order after the colours) among the coloured ones, and the analytic
// support forces of a resting column on two threads.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "service/contact/impulse/impulse_method.h"
#include "service/physics/body_settings.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;

constexpr double kG = 9.81;  // m/s^2

// A pile of 384 boxes and spheres (half sizes 0.05-0.15 m, so 0.1-10 kg
// at the default density 1000 kg/m^3) on a jittered 8 x 8 x 6 lattice
// dropped onto the ground, moving sideways and bouncing (e = 0.3): enough
// pairs that the passes run colour by colour (kMinColouredGroups); and a
// 6-link chain of spheres on ball joints hanging from the world into it,
// whose contacts keep their order after the colours.
World RandomPile(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> size(0.05, 0.15), jitter(-0.01, 0.01), speed(-1.0, 1.0);
  World world;
  AddGround(world, 0.3, 0.5);
  for (int k = 0; k < 384; ++k) {
    const Vec3 p(0.32 * (k % 8) + jitter(rng), 0.32 * ((k / 8) % 8) + jitter(rng), 0.16 + 0.32 * (k / 64));
    const Vec3 v(speed(rng), speed(rng), 0.0);
    if (k % 3 == 0) {
      AddSphere(world, size(rng), p, 0.3, 0.5, v);
    } else {
      AddBox(world, Vec3(size(rng), size(rng), size(rng)), p, 0.3, 0.5, v);
    }
  }
  BodyId above = kWorldBody;
  for (int i = 0; i < 6; ++i) {
    const Vec3 p(1.1, 1.1, 3.0 - 0.2 * i);
    const BodyId link = AddSphere(world, 0.08, p, 0.3, 0.5);
    JointSettings joint;
    joint.body_a = link;
    joint.body_b = above;
    joint.anchor = p + Vec3(0, 0, 0.1);
    JointId id = 0;
    EXPECT_TRUE(world.AddJoint(joint, &id).ok());
    above = link;
  }
  return world;
}

struct PileRun {
  uint64_t hash = 0;
  std::vector<double> impulses;  // every contact's normal impulse in the last step
  int iterations = 0;            // summed over the steps
  size_t pairs = 0;              // the most body pairs in contact at any step
};

size_t PairsInContact(const ContactSet& contacts) {
  std::set<std::pair<int, int>> pairs;
  for (const Contact& c : contacts) pairs.insert({c.a, c.b});
  return pairs.size();
}

PileRun RunPile(uint32_t seed, int threads, int steps) {
  World world = RandomPile(seed);
  CollisionDetector detector;
  EXPECT_TRUE(detector.SetThreads(threads).ok());
  ImpulseMethod method;
  ContactSet contacts;
  PileRun run;
  for (int s = 0; s < steps; ++s) {
    run.iterations += method.Step(world, detector, &contacts).iterations;
    run.pairs = std::max(run.pairs, PairsInContact(contacts));
  }
  run.hash = HashWorldState(world);
  for (const Contact& c : contacts) run.impulses.push_back(c.normal_value);
  return run;
}

// Verifies that the colour-by-colour passes end on the same state, the same
// contact impulses and the same iteration count bit for bit on 1, 2 and 4
// threads, for two random piles through their landing (collision phase,
// time of impact) and settling (contact phase, split impulse), with a
// jointed chain among the coloured bodies.
TEST(ImpulseStages, SameStateOnAnyNumberOfThreads) {
  // let oneTBB run four threads even on a two-core machine
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  for (const uint32_t seed : {1u, 2u}) {
    const PileRun serial = RunPile(seed, 1, 90);
    // the coloured passes need 256 pairs (kMinColouredGroups) in a step
    EXPECT_GT(serial.pairs, 256u) << "seed " << seed << ": too few pairs to colour";
    std::printf("seed %u: %zu pairs at most\n", seed, serial.pairs);
    for (const int threads : {2, 4}) {
      const PileRun run = RunPile(seed, threads, 90);
      EXPECT_EQ(run.hash, serial.hash) << "seed " << seed << ", " << threads << " threads";
      EXPECT_EQ(run.iterations, serial.iterations) << "seed " << seed << ", " << threads << " threads";
      ASSERT_EQ(run.impulses.size(), serial.impulses.size()) << "seed " << seed;
      for (size_t k = 0; k < run.impulses.size(); ++k) {
        EXPECT_EQ(run.impulses[k], serial.impulses[k]) << "seed " << seed << ", contact " << k;
      }
    }
  }
}

// Verifies that 64 columns of five boxes of 0.1 to 10 kg each (random
// sizes, 320 pairs: solved colour by colour) resting on the ground, solved
// on two threads, hold still and that the ground carries their weight:
// its contacts' normal impulses sum to m g h each step.
TEST(ImpulseStages, RestingColumnsCarryTheirWeightOnTwoThreads) {
  std::mt19937 rng(5);
  // half sizes: 0.1 to 10 kg at 1000 kg/m^3
  std::uniform_real_distribution<double> half(0.0232, 0.1077);
  World world;
  AddGround(world, 0.0, 0.5);
  double mass = 0.0;
  std::vector<BodyId> tops;
  std::vector<Vec3> tops0;
  for (int c = 0; c < 64; ++c) {
    double z = 0.0;
    BodyId top = 0;
    for (int k = 0; k < 5; ++k) {
      const double h = half(rng);
      top = AddBox(world, h, Vec3(0.3 * (c % 8), 0.3 * (c / 8), z + h), 0.0, 0.5);
      z += 2.0 * h;
      mass += world.Find(top)->mass;
    }
    tops.push_back(top);
    tops0.push_back(world.Find(top)->x);
  }
  CollisionDetector detector;
  ASSERT_TRUE(detector.SetThreads(2).ok());
  ImpulseMethod method;
  ContactSet contacts;
  for (int s = 0; s < 240; ++s) method.Step(world, detector, &contacts);
  double ground = 0.0;
  for (const Contact& c : contacts) {
    if (c.a == 0 || c.b == 0) ground += c.normal_value;
  }
  // tolerance: the contact phase stops at velocity_tolerance (1e-4 m/s,
  // 1/400 of g h = 0.041 m/s); the ground's rows together come within 1e-3
  EXPECT_NEAR(ground, mass * kG * world.dt, 1e-3 * mass * kG * world.dt);
  for (size_t c = 0; c < tops.size(); ++c) {
    // the faces rest within the slop (1 mm), as a serial sweep leaves them
    EXPECT_LT((world.Find(tops[c])->x - tops0[c]).norm(), 1e-3) << "column " << c;
  }
}

}  // namespace
}  // namespace contactsim
