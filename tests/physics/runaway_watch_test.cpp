// Tests of the blow-up detector: motion the inputs explain never trips it,
// growth no input explains does, within a few steps, and a non-finite state
// at once.
#include "service/physics/runaway_watch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "service/physics/body_settings.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

BodyId AddBall(World& world, double mass, const Vec3& x, const Vec3& v, bool kinematic = false) {
  BodySettings s;
  s.radius = 0.1;
  s.mass = mass;
  s.position = x;
  s.linear_velocity = v;
  s.kinematic = kinematic;
  if (kinematic) s.mass.reset();
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return world.AddBody(b);
}

// One step of free flight with the watch around it.
Status WatchedStep(World& world, RunawayWatch& watch) {
  watch.BeforeStep(world);
  world.AccumulateForces();
  IntegrateMomenta(world, world.dt);
  IntegratePositions(world, world.dt);
  world.FinishStep();
  return watch.AfterStep(world);
}

// Verifies that bodies of 0.1 to 10 kg falling freely for 100 s (to 981 m/s)
// and one pushed by a 1 kN wrench for 10 s do not trip the watch: gravity's
// work is in V, the wrench's is counted.
TEST(RunawayWatch, FreeFallAndAppliedForcesAreNotBlowUps) {
  World world;
  for (double m : {0.1, 1.0, 10.0}) AddBall(world, m, Vec3(m, 0, 0), Vec3(0, 0, 1));
  const BodyId pushed = AddBall(world, 0.1, Vec3(0, 5, 0), Vec3::Zero());
  TimedWrench w;
  w.body = pushed;
  w.force = Vec3(1000, 0, 0);
  w.remaining = 10.0;
  world.AddWrench(w);
  RunawayWatch watch;
  for (int i = 0; i < 24000; ++i) ASSERT_TRUE(WatchedStep(world, watch).ok()) << i;
  EXPECT_GT(world.Find(pushed)->LinearVelocity().x(), 9e4);
}

// Verifies that a state growing geometrically (each step's velocity 1.5
// times the last, as a diverging solver does) trips the watch within 40 steps
// for every mass, and that the message names the step and the body.
TEST(RunawayWatch, GeometricGrowthTripsItWithinFortySteps) {
  for (double m : {0.1, 1.0, 10.0}) {
    World world;
    AddBall(world, 10.0, Vec3(0, 0, 1), Vec3::Zero());
    const BodyId id = AddBall(world, m, Vec3(1, 0, 1), Vec3(0.1, 0, 0));
    RunawayWatch watch;
    Status st;
    int steps = 0;
    for (; steps < 200 && st.ok(); ++steps) {
      RigidBody& b = *world.Find(id);
      b.P *= 1.5;
      st = WatchedStep(world, watch);
    }
    ASSERT_FALSE(st.ok()) << "m = " << m;
    EXPECT_LE(steps, 40) << "m = " << m;
    EXPECT_EQ(st.code(), StatusCode::kFailedPrecondition);
    EXPECT_NE(st.message().find("blew up at step"), std::string::npos) << st.message();
    EXPECT_NE(st.message().find("body " + std::to_string(id)), std::string::npos) << st.message();
  }
}

// Verifies that a non-finite position, momentum or orientation trips it at
// the step it appears.
TEST(RunawayWatch, NonFiniteStateTripsItAtOnce) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (int field = 0; field < 3; ++field) {
    World world;
    const BodyId id = AddBall(world, 1.0, Vec3(0, 0, 1), Vec3::Zero());
    RunawayWatch watch;
    ASSERT_TRUE(WatchedStep(world, watch).ok());
    RigidBody& b = *world.Find(id);
    if (field == 0) b.x.x() = nan;
    if (field == 1) b.P.z() = inf;
    if (field == 2) b.q.w() = nan;
    const Status st = watch.AfterStep(world);
    EXPECT_FALSE(st.ok()) << field;
    EXPECT_NE(st.message().find("non-finite"), std::string::npos) << st.message();
  }
}

// Verifies that a velocity a command sets (here 1,000 m/s) is a new baseline
// after Rebase, not a blow-up, while the same jump without one is.
TEST(RunawayWatch, RebaseAcceptsWhatACommandSet) {
  World world;
  const BodyId id = AddBall(world, 1.0, Vec3(0, 0, 1), Vec3::Zero());
  RunawayWatch watch;
  ASSERT_TRUE(WatchedStep(world, watch).ok());
  world.Find(id)->P = Vec3(1000, 0, 0);
  EXPECT_FALSE(WatchedStep(world, watch).ok());
  watch.Rebase(world);
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(WatchedStep(world, watch).ok());
}

}  // namespace
}  // namespace contactsim
