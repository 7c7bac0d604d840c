// Sleeping islands (service/contact/sleep/island_sleep.h) under every
// registered contact method: a settled body falls asleep and stays bit for
// bit where it slept, an awake body or a command wakes it and acts, a
// swinging pendulum never sleeps, and with sleep off a step is exactly the
// method's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "service/contact/sleep/island_sleep.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::MethodConfig;

constexpr double kHalf = 0.1;          // m, half size of the boxes
constexpr double kSettleLimit = 6.0;   // s: a dropped box settles in < 1 s; sleep needs 0.5 s more

// A method with sleeping on, stepped through IslandSleep.
struct SleepSim : testing::MethodSim {
  IslandSleep sleep;
  explicit SleepSim(const MethodConfig& c) : MethodSim(c.method, c.params) { world.sleep.enabled = true; }
  StepStats Step() { return sleep.Step(world, *method, detector, &contacts); }
  // steps until every dynamic body sleeps or `limit` s pass; true when asleep
  bool StepUntilAsleep(double limit) {
    const double end = world.time + limit;
    while (world.time < end) {
      Step();
      if (AllAsleep()) return true;
    }
    return false;
  }
  bool AllAsleep() const {
    for (const RigidBody& b : world.bodies()) {
      if (b.IsDynamic() && !b.asleep()) return false;
    }
    return true;
  }
};

// A stack of `n` cubes on the ground, resting within a small gap of each other.
std::vector<BodyId> AddStack(World& world, int n) {
  std::vector<BodyId> ids;
  for (int i = 0; i < n; ++i) ids.push_back(AddBox(world, kHalf, Vec3(0, 0, kHalf + 2 * kHalf * i + 1e-3 * (i + 1)), 0.0, 0.5));
  return ids;
}

class IslandSleepTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies that a box dropped 5 cm onto the ground falls asleep once
// settled (resting on its face, within 1 cm of z = half), and that its
// pose then stays bit for bit the same, with zero momentum, for 2 s more.
TEST_P(IslandSleepTest, DroppedBoxFallsAsleepAndKeepsItsPoseBitForBit) {
  SleepSim sim(GetParam());
  AddGround(sim.world, 0.0, 0.5);
  const BodyId box = AddBox(sim.world, kHalf, Vec3(0, 0, kHalf + 0.05), 0.0, 0.5);
  ASSERT_TRUE(sim.StepUntilAsleep(kSettleLimit)) << GetParam().label << ": still awake at t = " << sim.world.time;
  const RigidBody slept = *sim.world.Find(box);
  std::printf("[%s] asleep at t = %.3f s, z = %.6f m\n", GetParam().label.c_str(), sim.world.time, slept.x.z());
  EXPECT_NEAR(slept.x.z(), kHalf, 0.01);
  EXPECT_EQ(slept.sleep_island, box);
  for (int i = 0; i < 480; ++i) sim.Step();
  const RigidBody& now = *sim.world.Find(box);
  EXPECT_TRUE(now.asleep());
  EXPECT_EQ(now.x, slept.x);
  EXPECT_EQ(now.q.coeffs(), slept.q.coeffs());
  EXPECT_EQ(now.P, Vec3::Zero());
  EXPECT_EQ(now.L, Vec3::Zero());
  EXPECT_EQ(sim.sleep.stats().sleeping, 1);
  // two sleeping bodies (the box and the ground) are never a candidate pair
  EXPECT_EQ(sim.detector.stats().candidate_pairs, 0);
}

// Drops or throws a ball at the top box of a sleeping stack of three and
// steps 1 s: no contact of the ball may touch a sleeping box (the stack
// woke before it arrived). Returns how far the top box moved.
double HitSleepingStack(SleepSim& sim, const Vec3& from_top, const Vec3& v) {
  AddGround(sim.world, 0.0, 0.5);
  const std::vector<BodyId> stack = AddStack(sim.world, 3);
  EXPECT_TRUE(sim.StepUntilAsleep(kSettleLimit)) << "the stack did not sleep";
  const Vec3 top_slept = sim.world.Find(stack.back())->x;
  const BodyId ball = AddSphere(sim.world, 0.05, top_slept + from_top, 0.0, 0.5, v);
  double moved = 0.0;
  for (int i = 0; i < 240; ++i) {
    std::vector<bool> was_asleep;
    for (const RigidBody& b : sim.world.bodies()) was_asleep.push_back(b.asleep());
    sim.Step();
    EXPECT_EQ(sim.sleep.stats().woken_late, 0) << "step " << i;
    // a body asleep before and after the step was static during it (once
    // the ball sleeps too, its contacts are the kept ones: island_sleep.h)
    for (const Contact& c : sim.contacts) {
      const int other = c.id_a == ball ? c.b : c.id_b == ball ? c.a : -1;
      if (other >= 0 && !sim.world.Find(ball)->asleep()) {
        EXPECT_FALSE(was_asleep[other] && sim.world.bodies()[other].asleep()) << "step " << i << ": the ball met a sleeper";
      }
    }
    moved = std::max(moved, (sim.world.Find(stack.back())->x - top_slept).norm());
  }
  return moved;
}

// Verifies that a sleeping stack wakes before a ball dropped 0.3 m onto its
// top box lands, and that the top box then answers: it moves (a sleeping
// box would not move by a single bit). The 8 kg box on a rigid stack under
// a 0.5 kg ball moves little (impulse, its face rows solved as blocks:
// 8e-8 m; Lemke's exact rigid answer 5e-15 m), so any motion counts.
TEST_P(IslandSleepTest, SleepingStackWakesWhenABallIsDroppedOnIt) {
  SleepSim sim(GetParam());
  const double moved = HitSleepingStack(sim, Vec3(0.02, 0, 0.3), Vec3::Zero());
  std::printf("[%s] top box moved %.3e m under the dropped ball\n", GetParam().label.c_str(), moved);
  EXPECT_GT(moved, 0.0);
}

// Verifies that a ball thrown at 4 m/s at the side of a sleeping stack's
// top box wakes the stack before it arrives and pushes the top box. An
// inelastic hit of the 0.52 kg ball on the 8 kg box gives the box
// 0.52 * 4 / 8.52 = 0.246 m/s, which friction (mu = 0.5 on the box below)
// stops within v^2 / (2 mu g) = 6.2 mm; the box must slide at least half
// of that (measured 6.2 to 13 mm across the methods).
TEST_P(IslandSleepTest, SleepingStackWakesAndReactsWhenABallIsThrownAtIt) {
  SleepSim sim(GetParam());
  const double moved = HitSleepingStack(sim, Vec3(-0.4, 0, 0.02), Vec3(4.0, 0, 0));
  std::printf("[%s] top box moved %.4f m after the hit\n", GetParam().label.c_str(), moved);
  EXPECT_GT(moved, 0.0031);
}

// Verifies that a velocity set on a sleeping box (with no wake call, as an
// in-process caller might) and an impulse after WakeTouching (as the server
// does) both take effect: the box slides by about v t along x.
TEST_P(IslandSleepTest, VelocityAndImpulseOnASleepingBoxTakeEffect) {
  SleepSim sim(GetParam());
  AddGround(sim.world, 0.0, 0.0);  // frictionless: the box glides
  const BodyId box = AddBox(sim.world, kHalf, Vec3(0, 0, kHalf + 0.01), 0.0, 0.0);
  ASSERT_TRUE(sim.StepUntilAsleep(kSettleLimit)) << GetParam().label;
  const double x0 = sim.world.Find(box)->x.x();
  sim.world.Find(box)->SetVelocity(Vec3(1.0, 0, 0), Vec3::Zero());
  for (int i = 0; i < 24; ++i) sim.Step();  // 0.1 s
  EXPECT_NEAR(sim.world.Find(box)->x.x() - x0, 0.1, 0.01) << GetParam().label;
  // stop it by an impulse -m v through the server's path
  RigidBody* b = sim.world.Find(box);
  b->ApplyImpulse(-b->P, b->x);
  WakeTouching(sim.world, box);
  ASSERT_TRUE(sim.StepUntilAsleep(kSettleLimit));
  const double x1 = sim.world.Find(box)->x.x();
  sim.world.Find(box)->ApplyImpulse(Vec3(0.5 * sim.world.Find(box)->mass, 0, 0), sim.world.Find(box)->x);
  WakeTouching(sim.world, box);
  for (int i = 0; i < 48; ++i) sim.Step();  // 0.2 s at 0.5 m/s
  EXPECT_NEAR(sim.world.Find(box)->x.x() - x1, 0.1, 0.01) << GetParam().label;
}

// Verifies that a wrench on a sleeping box wakes it (World::AddWrench): an
// upward force of twice its weight for 0.2 s lifts it by about
// g t^2 / 2 = 0.196 m.
TEST_P(IslandSleepTest, ForceOnASleepingBoxWakesAndLiftsIt) {
  SleepSim sim(GetParam());
  AddGround(sim.world, 0.0, 0.5);
  const BodyId box = AddBox(sim.world, kHalf, Vec3(0, 0, kHalf + 0.01), 0.0, 0.5);
  ASSERT_TRUE(sim.StepUntilAsleep(kSettleLimit)) << GetParam().label;
  const double z0 = sim.world.Find(box)->x.z();
  const double m = sim.world.Find(box)->mass;
  sim.world.AddWrench({box, Vec3(0, 0, 2 * m * testing::kG), Vec3::Zero(), 0.2});
  EXPECT_FALSE(sim.world.Find(box)->asleep());
  for (int i = 0; i < 48; ++i) sim.Step();
  EXPECT_NEAR(sim.world.Find(box)->x.z() - z0, 0.5 * testing::kG * 0.04, 0.02) << GetParam().label;
}

// Verifies that a pendulum swinging from 1 rad on a 1 m arm never sleeps
// over 5 s: its speed drops below the threshold only near the turning
// points, for far less than time_to_sleep. Methods without joints are
// skipped (their contract refuses the world).
TEST_P(IslandSleepTest, SwingingPendulumNeverSleeps) {
  SleepSim sim(GetParam());
  const Vec3 pivot(0, 0, 2);
  const BodyId bob = AddSphere(sim.world, 0.05, pivot + Vec3(std::sin(1.0), 0, -std::cos(1.0)), 0.0);
  testing::AddJoint(sim.world, JointKind::kDistance, bob, kWorldBody, pivot);
  if (!testing::ContractOf(GetParam()).joints) GTEST_SKIP() << GetParam().label << " does not simulate joints";
  double most_rest = 0.0;
  while (sim.world.time < 5.0) {
    sim.Step();
    ASSERT_FALSE(sim.world.Find(bob)->asleep()) << "t = " << sim.world.time;
    most_rest = std::max(most_rest, sim.world.Find(bob)->rest_time);
  }
  std::printf("[%s] longest rest of the swinging bob: %.4f s\n", GetParam().label.c_str(), most_rest);
  EXPECT_LT(most_rest, 0.1);
}

// Verifies that a pendulum hanging at rest falls asleep with its joint held
// back (a joint between a static sleeper and the world has no mass to
// invert), and that an impulse wakes it into a swing whose arm still holds
// its length to 1 mm: the joint is back.
TEST_P(IslandSleepTest, HangingPendulumSleepsAndSwingsOnItsJointWhenWoken) {
  SleepSim sim(GetParam());
  const Vec3 pivot(0, 0, 2);
  const BodyId bob = AddSphere(sim.world, 0.05, pivot - Vec3(0, 0, 1), 0.0);
  testing::AddJoint(sim.world, JointKind::kDistance, bob, kWorldBody, pivot);
  if (!testing::ContractOf(GetParam()).joints) GTEST_SKIP() << GetParam().label << " does not simulate joints";
  ASSERT_TRUE(sim.StepUntilAsleep(kSettleLimit)) << GetParam().label;
  for (int i = 0; i < 24; ++i) sim.Step();
  EXPECT_EQ(sim.world.joints().size(), 1u);  // given back after every step
  RigidBody* b = sim.world.Find(bob);
  b->ApplyImpulse(Vec3(b->mass * 2.0, 0, 0), b->x);  // 2 m/s: swings up about 0.2 m
  WakeTouching(sim.world, bob);
  double drift = 0.0, highest = 0.0;
  for (int i = 0; i < 240; ++i) {
    sim.Step();
    drift = std::max(drift, std::abs((sim.world.Find(bob)->x - pivot).norm() - 1.0));
    highest = std::max(highest, sim.world.Find(bob)->x.z() - (pivot.z() - 1.0));
  }
  EXPECT_LT(drift, 1e-3) << GetParam().label;
  EXPECT_NEAR(highest, 2.0 * 2.0 / (2 * testing::kG), 0.02) << GetParam().label;
}

// Verifies that with sleep off IslandSleep::Step is the method's own step:
// the same states bit for bit, and nobody's rest timer moves.
TEST_P(IslandSleepTest, SleepOffStepsExactlyAsTheMethod) {
  SleepSim with(GetParam());
  testing::MethodSim bare(GetParam().method, GetParam().params);
  with.world.sleep.enabled = false;
  for (World* w : {&with.world, &bare.world}) {
    AddGround(*w, 0.0, 0.5);
    AddStack(*w, 2);
  }
  for (int i = 0; i < 360; ++i) {
    with.Step();
    bare.Step();
  }
  EXPECT_EQ(HashWorldState(with.world), HashWorldState(bare.world));
  for (const RigidBody& b : with.world.bodies()) EXPECT_EQ(b.rest_time, 0.0);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, IslandSleepTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         [](const ::testing::TestParamInfo<MethodConfig>& info) { return info.param.label; });

}  // namespace
}  // namespace contactsim
