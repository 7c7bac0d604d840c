// Tests of the barrier method (IPC on affine bodies): the guarantee that no
// two bodies ever touch, checked at every step with the narrowphase's own
// signed distance (exact for planes and spheres, a lower bound of the
// distance between two apart boxes), plus rest, a stack and friction.
#include "service/contact/barrier/barrier_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "service/collision/narrowphase.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;       // m/s^2
constexpr double kDHat = 1e-3;    // m, the default activation distance

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::AddValidBody;
using Sim = testing::MethodSim;

using testing::SmallestGap;
// Verifies that a box resting on the ground never touches it, carries its
// weight through the barrier and stays within d_hat of where it started.
TEST(BarrierMethod, RestingBoxNeverTouchesAndCarriesItsWeight) {
  Sim sim("barrier");
  AddGround(sim.world, 0.0, 0.5);
  const double half = 0.1;
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, half + 0.5 * kDHat), 0.0, 0.5);
  const Vec3 x0 = sim.world.Find(id)->x;
  double worst = std::numeric_limits<double>::infinity();
  StepStats stats;
  for (int i = 0; i < 240; ++i) {
    stats = sim.Step();
    worst = std::min({worst, SmallestGap(sim.world), stats.residual});
  }
  const RigidBody& b = *sim.world.Find(id);
  EXPECT_GT(worst, 0.0);
  EXPECT_LT((b.x - x0).norm(), kDHat);
  double total = 0.0;
  for (const Contact& c : sim.contacts) total += c.normal_value;
  EXPECT_NEAR(total, b.mass * kG, 0.05 * b.mass * kG);
  std::printf("barrier: resting box, smallest gap %.3g m, kappa %.3g N/m, %d Newton iterations\n", worst,
              static_cast<BarrierMethod*>(sim.method.get())->barrier_stiffness(), stats.iterations);
}

// Verifies that a stack of five boxes stands for 10 s without any two
// bodies touching: every box within 1 cm of where it started.
TEST(BarrierMethod, StackOfFiveBoxesStandsWithoutContact) {
  Sim sim("barrier");
  AddGround(sim.world, 0.0, 0.5);
  const double half = 0.1;
  for (int i = 0; i < 5; ++i) AddBox(sim.world, half, Vec3(0, 0, half * (1 + 2 * i) + (i + 0.5) * kDHat), 0.0, 0.5);
  const World start = sim.world;
  double worst_gap = std::numeric_limits<double>::infinity(), worst_move = 0.0;
  for (int i = 0; i < 2400; ++i) {
    const StepStats stats = sim.Step();
    worst_gap = std::min({worst_gap, SmallestGap(sim.world), stats.residual});
    for (size_t k = 0; k < sim.world.bodies().size(); ++k) {
      worst_move = std::max(worst_move, (sim.world.bodies()[k].x - start.bodies()[k].x).norm());
    }
  }
  EXPECT_GT(worst_gap, 0.0);
  EXPECT_LT(worst_move, 1e-2);
  std::printf("barrier: five-box stack 10 s, smallest gap %.3g m, largest displacement %.3g m\n", worst_gap,
              worst_move);
}

// Verifies the guarantee against tunnelling: a sphere at 100 m/s (42 cm per
// step) hits a 1 cm static box, never touches it and stays on its side.
TEST(BarrierMethod, SphereAtHundredMetresPerSecondNeverTouchesThinBox) {
  Sim sim("barrier");
  sim.world.gravity.setZero();
  BodySettings wall;
  wall.shape = ShapeType::kBox;
  wall.half_extents = Vec3(0.005, 0.5, 0.5);
  wall.fixed = true;
  wall.restitution = 0.0;
  AddValidBody(sim.world, wall);
  const double r = 0.05;
  const BodyId ball = AddSphere(sim.world, r, Vec3(-1.0, 0, 0), 0.0, 0.5, Vec3(100.0, 0, 0));
  double worst = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 60; ++i) {
    const StepStats stats = sim.Step();
    worst = std::min({worst, SmallestGap(sim.world), stats.residual});
  }
  EXPECT_GT(worst, 0.0);
  EXPECT_LT(sim.world.Find(ball)->x.x(), -0.005 - r);
  std::printf("barrier: sphere at 100 m/s, smallest gap %.3g m\n", worst);
}

// Verifies lagged smoothed friction (IPC sec. 5): a box sliding at 3 m/s
// with mu = 0.4 stops after v0^2 / (2 mu g) within 5% and stays stopped
// (static friction below the slip speed eps_v).
TEST(BarrierMethod, SlidingBoxStopsAtTheCoulombDistance) {
  const double mu = 0.4, v0 = 3.0, half = 0.1;
  Sim sim("barrier");
  AddGround(sim.world, 0.0, mu);
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, half + 0.5 * kDHat), 0.0, mu, Vec3(v0, 0, 0));
  for (int i = 0; i < 480; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  const double expected = v0 * v0 / (2.0 * mu * kG);
  EXPECT_NEAR(b.x.x(), expected, 0.05 * expected);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-3);  // below eps_v: held by static friction
  std::printf("barrier: stopping distance %.4f m, analytic %.4f m (%+.2f%%)\n", b.x.x(), expected,
              100.0 * (b.x.x() - expected) / expected);
}

// Verifies that a free sphere keeps its spin (affine_prediction.h: the
// rotation is predicted by the midpoint rule): spinning at 5, 10 and 20
// rad/s in zero gravity for 1 s, it ends at its initial rate to 1e-9
// (implicit Euler's prediction kept 90%, 74% and 48%).
TEST(BarrierMethod, FreeSphereKeepsItsSpin) {
  for (const double rate : {5.0, 10.0, 20.0}) {  // rad/s
    Sim sim("barrier");
    sim.world.gravity.setZero();
    BodySettings s;
    s.shape = ShapeType::kSphere;
    s.radius = 0.1;
    s.angular_velocity = Vec3(0, rate, 0);
    const BodyId id = AddValidBody(sim.world, s);
    for (int i = 0; i < 240; ++i) sim.Step();
    const double kept = sim.world.Find(id)->AngularVelocity().norm() / rate;
    std::printf("barrier: free sphere at %g rad/s keeps %.12f of its spin after 1 s\n", rate, kept);
    EXPECT_NEAR(kept, 1.0, 1e-9) << rate << " rad/s";
  }
}

// Verifies parameter validation: a bad value is named and changes nothing.
TEST(BarrierMethod, RejectsBadParametersAndKeepsTheOldOnes) {
  BarrierMethod m;
  const Status st = m.SetParams({{"max_iterations", "8"}, {"d_hat", "0"}});
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("d_hat"), std::string::npos) << st.message();
  EXPECT_EQ(m.params().max_iterations, 50);
}

// How far a cube of `mass` placed flush on the ground (mu for both), let
// rest 0.2 s and launched along x at v0, slides, over v0^2 / (2 mu g).
double LaunchedCubeSlide(const ParamMap& params, double mass, double mu, double v0) {
  Sim sim("barrier", params);
  AddGround(sim.world, 0.0, mu);
  const double half = 0.1;
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(half);
  box.mass = mass;
  box.position = Vec3(0, 0, half);
  box.friction = mu;
  const BodyId id = AddValidBody(sim.world, box);
  while (sim.world.time < 0.2) sim.Step();
  RigidBody& b = *sim.world.Find(id);
  const double x0 = b.x.x();
  b.SetVelocity(Vec3(v0, 0, 0), Vec3::Zero());
  while (sim.world.time < 0.2 + v0 / (mu * kG) + 0.3) sim.Step();
  return (sim.world.Find(id)->x.x() - x0) / (v0 * v0 / (2 * mu * kG));
}

// Verifies IPC's lagged iterations (friction_lag_passes, barrier_params.h):
// a cube placed flush and launched rocks as it slides, and its friction
// lagged once from the step's start trails its normal forces by a step
// (1.8% short at mu 0.4, 6.4% at mu 0.8); with the lag repeated until it
// settles the slide is closer at every mass and friction, 0.83% and 2.0%
// short (20 passes to a tolerance of 1e-6 give the same: what is left is
// not the lag).
TEST(BarrierMethod, LaggedIterationsBringALaunchedCubeToCoulombsDistance) {
  for (double mass : {0.1, 1.0, 10.0}) {
    for (double mu : {0.4, 0.8}) {
      const double once = LaunchedCubeSlide({}, mass, mu, 2.0);
      const double lagged = LaunchedCubeSlide({{"friction_lag_passes", "4"}}, mass, mu, 2.0);
      std::printf("barrier: launched cube m %4.1f kg mu %.1f slides %.4f of Coulomb's distance lagged once, %.4f "
                  "lagged until settled\n", mass, mu, once, lagged);
      EXPECT_NEAR(lagged, 1.0, 0.025) << "m " << mass << " mu " << mu;
      EXPECT_LT(std::abs(lagged - 1.0), std::abs(once - 1.0)) << "m " << mass << " mu " << mu;
    }
  }
}

}  // namespace
}  // namespace contactsim
