// Scenes from the contact-methods issue that every method must pass, run
// through the registry by name: a box on a 30 degree incline (static and
// dynamic Coulomb friction), and the impulse method's stack and tunnelling
// cases.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "service/contact/contact_method.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/slope.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2
constexpr double kPi = 3.14159265358979323846;

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::AddValidBody;

using Sim = testing::MethodSim;

// A cube of half size 0.1 m resting on a slope tilted by `angle` about y
// (testing::AddSlope), its bottom face on the slope. Returns the cube's id;
// `downhill` is the unit vector down the slope.
BodyId AddBoxOnIncline(World& world, double angle, double mu, Vec3* downhill) {
  const Quat tilt = testing::AddSlope(world, angle, mu, downhill);
  const Vec3 normal = tilt * Vec3::UnitZ();
  const double half = 0.1;
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(half);
  box.position = half * normal;
  box.orientation = Eigen::Vector4d(tilt.w(), tilt.x(), tilt.y(), tilt.z());
  box.restitution = 0.0;
  box.friction = mu;
  return AddValidBody(world, box);
}

// Runs for every method named in the instantiation below.
class EveryMethodTest : public ::testing::TestWithParam<const char*> {};

// Verifies static friction: with mu = 0.7 > tan 30 deg the box holds, moving
// less than 1 mm in 5 s.
TEST_P(EveryMethodTest, BoxHoldsWhenFrictionExceedsTheSlope) {
  Sim sim(GetParam());
  Vec3 downhill;
  const BodyId id = AddBoxOnIncline(sim.world, kPi / 6.0, 0.7, &downhill);
  for (int i = 0; i < 120; ++i) sim.Step();  // settle (penalty sinks to its weight depth)
  const Vec3 x0 = sim.world.Find(id)->x;
  for (int i = 0; i < 1200; ++i) sim.Step();  // 5 s
  const double drift = (sim.world.Find(id)->x - x0).norm();
  EXPECT_LT(drift, 1e-3) << GetParam();
  std::printf("%s: drift on the incline over 5 s %.3g m\n", GetParam(), drift);
}

// Verifies dynamic friction: with mu = 0.3 the box slides down with
// a = g (sin 30 - mu cos 30) within 3%, measured as the distance travelled
// in 1 s, s = a t^2 / 2.
TEST_P(EveryMethodTest, BoxSlidesWithCoulombAcceleration) {
  const double mu = 0.3, angle = kPi / 6.0;
  Sim sim(GetParam());
  Vec3 downhill;
  const BodyId id = AddBoxOnIncline(sim.world, angle, mu, &downhill);
  const double a = kG * (std::sin(angle) - mu * std::cos(angle));
  // the first steps settle the contact; measure over the second after them
  for (int i = 0; i < 24; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  const Vec3 x0 = b.x;
  const double v0 = b.LinearVelocity().dot(downhill);
  for (int i = 0; i < 240; ++i) sim.Step();
  const double t = 240 * sim.world.dt;
  const double travelled = (b.x - x0).dot(downhill);
  const double expected = v0 * t + 0.5 * a * t * t;
  EXPECT_NEAR(travelled, expected, 0.03 * expected) << GetParam();
  EXPECT_LT(b.AngularVelocity().norm(), 1e-2) << GetParam();  // slides, does not tumble
  std::printf("%s: slid %.4f m in 1 s, analytic %.4f m (%+.2f%%)\n", GetParam(), travelled, expected,
              100.0 * (travelled - expected) / expected);
}

// Verifies that with e = 0 a dropped sphere does not bounce: after the first
// contact its lowest point never rises more than 1% of the drop height.
TEST_P(EveryMethodTest, SphereWithZeroRestitutionDoesNotBounce) {
  const double r = 0.1, h = 1.0;
  Sim sim(GetParam());
  AddGround(sim.world, 0.0, 0.5);
  const BodyId ball = AddSphere(sim.world, r, Vec3(0, 0, h + r), 0.0);
  bool touched = false;
  double highest = 0.0;
  for (int i = 0; i < 480; ++i) {
    sim.Step();
    const double z = sim.world.Find(ball)->x.z() - r;
    touched = touched || z < 2e-3;
    if (touched) highest = std::max(highest, z);
  }
  EXPECT_TRUE(touched) << GetParam();
  EXPECT_LT(highest, 0.01 * h) << GetParam();
  std::printf("%s: e = 0, highest point after contact %.3g m\n", GetParam(), highest);
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryMethodTest, ::testing::Values("impulse", "penalty", "xpbd", "lcp"));

// Methods that stand stacks and collide a face's corners together.
class StackingMethodTest : public ::testing::TestWithParam<const char*> {};

// Verifies that a stack of five boxes stays standing for 10 s: every box
// within 1 cm of where it started.
TEST_P(StackingMethodTest, StackOfFiveBoxesStandsForTenSeconds) {
  Sim sim(GetParam());
  AddGround(sim.world, 0.0, 0.5);
  const double half = 0.1;
  for (int i = 0; i < 5; ++i) AddBox(sim.world, half, Vec3(0, 0, half * (1 + 2 * i)), 0.0, 0.5);
  World start = sim.world;
  for (int i = 0; i < 2400; ++i) sim.Step();
  double worst = 0.0;
  for (size_t i = 0; i < sim.world.bodies().size(); ++i) {
    worst = std::max(worst, (sim.world.bodies()[i].x - start.bodies()[i].x).norm());
  }
  EXPECT_LT(worst, 1e-2) << GetParam();
  std::printf("%s: five-box stack, largest displacement after 10 s %.3g m\n", GetParam(), worst);
}

// Verifies that the four corners of a box landing flat collide together: it
// rebounds to e^2 h within 2% and does not start to spin (one corner after
// another would give the first the whole impulse and tip the box).
TEST_P(StackingMethodTest, BoxLandingFlatReboundsStraight) {
  const double e = 0.5, h = 1.0, half = 0.1;
  Sim sim(GetParam());
  AddGround(sim.world, e, 0.5);
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, h + half), e, 0.5);
  bool bounced = false;
  double apex = 0.0, last_vz = 0.0, worst_spin = 0.0;
  for (int i = 0; i < 480; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(id);
    const double vz = b.LinearVelocity().z();
    worst_spin = std::max(worst_spin, b.AngularVelocity().norm());
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z() - half);
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  EXPECT_NEAR(apex, e * e * h, 0.02 * e * e * h) << GetParam();
  EXPECT_LT(worst_spin, 1e-4) << GetParam();  // impulse: its velocity tolerance leaves ~2e-6 rad/s
  std::printf("%s: box landing flat rebounds to %.5f m (e^2 h = %.5f m), spin %.2g rad/s\n", GetParam(), apex,
              e * e * h, worst_spin);
}

INSTANTIATE_TEST_SUITE_P(Methods, StackingMethodTest, ::testing::Values("impulse", "xpbd", "lcp"));

// Verifies that a sphere at 50 m/s does not pass through a 2 cm thick static
// box (collision time by backtracking): it ends on the near side.
TEST(ImpulseScenarios, FastSphereDoesNotTunnelThroughThinBox) {
  Sim sim("impulse");
  sim.world.gravity.setZero();
  BodySettings wall;
  wall.shape = ShapeType::kBox;
  wall.half_extents = Vec3(0.01, 1.0, 1.0);  // 2 cm thick in x
  wall.fixed = true;
  wall.restitution = 0.0;
  AddValidBody(sim.world, wall);
  const double r = 0.05;
  const BodyId ball = AddSphere(sim.world, r, Vec3(-1.0, 0, 0), 0.0, 0.5, Vec3(50.0, 0, 0));
  for (int i = 0; i < 60; ++i) sim.Step();  // 50 m/s covers 0.21 m per step
  const RigidBody& b = *sim.world.Find(ball);
  EXPECT_LT(b.x.x(), -0.01 - r + 2e-3);  // on the near face, within the slop
  EXPECT_LT(b.LinearVelocity().x(), 1e-6);  // stopped (e = 0), not moving through
}

}  // namespace
}  // namespace contactsim
