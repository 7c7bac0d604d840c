// Tests of the xpbd method (extended position based dynamics) against
// analytic results (the stacks and the incline are in the mechanics suite,
// tests/contact/mechanics_*_test.cpp): a resting box carries its weight, a
// sliding box stops at the Coulomb distance, a dropped sphere rebounds to
// e^2 h, compliance gives the spring's sag, and parameters are validated.
#include "service/contact/xpbd/xpbd_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "service/physics/body_settings.h"
#include "service/physics/integrator.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::AddValidBody;
using Sim = testing::MethodSim;

// Verifies that a box resting on the ground stays put (the solve removes
// exactly what gravity's prediction adds) and that its contacts report the
// weight as a force.
TEST(XpbdMethod, RestingBoxStaysAndCarriesItsWeight) {
  Sim sim("xpbd");
  AddGround(sim.world, 0.0, 0.5);
  const double half = 0.1;
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, 0.5);
  const Vec3 x0 = sim.world.Find(id)->x;
  StepStats stats;
  for (int i = 0; i < 480; ++i) stats = sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  // one sub-step's gravity, g h^2, is the most the box can sink
  const int substeps = XpbdParams().substeps;
  const double h = sim.world.dt / substeps;
  EXPECT_LT((b.x - x0).norm(), kG * h * h + 1e-9);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-9);
  EXPECT_LT(b.AngularVelocity().norm(), 1e-9);
  ASSERT_EQ(sim.contacts.size(), 4u);
  double total = 0.0;
  for (const Contact& c : sim.contacts) total += c.normal_value;
  EXPECT_NEAR(total, b.mass * kG, 1e-6 * b.mass * kG);
  EXPECT_EQ(sim.method->ValueKind(), ContactValueKind::kForce);
  EXPECT_EQ(stats.substeps, substeps);
  EXPECT_EQ(stats.iterations, substeps);
}

// Verifies dynamic friction: a box sliding at 3 m/s with mu = 0.4 stops
// after v0^2 / (2 mu g) within 5%, and stays stopped.
TEST(XpbdMethod, SlidingBoxStopsAtTheCoulombDistance) {
  const double mu = 0.4, v0 = 3.0, half = 0.1;
  Sim sim("xpbd");
  AddGround(sim.world, 0.0, mu);
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, mu, Vec3(v0, 0, 0));
  for (int i = 0; i < 480; ++i) sim.Step();  // stops after v0 / (mu g) = 0.76 s
  const RigidBody& b = *sim.world.Find(id);
  const double expected = v0 * v0 / (2.0 * mu * kG);
  EXPECT_NEAR(b.x.x(), expected, 0.05 * expected);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-6);
  std::printf("xpbd: stopping distance %.4f m, analytic %.4f m (%+.2f%%)\n", b.x.x(), expected,
              100.0 * (b.x.x() - expected) / expected);
}

// Verifies restitution in the velocity pass: a sphere dropped from 1 m
// rebounds to e^2 h within 5% for e = 0.5 and 0.9.
TEST(XpbdMethod, DroppedSphereReboundsToRestitutionSquaredHeight) {
  for (const double e : {0.5, 0.9}) {
    const double r = 0.1, h = 1.0;
    Sim sim("xpbd");
    AddGround(sim.world, e, 0.5);
    const BodyId id = AddSphere(sim.world, r, Vec3(0, 0, h + r), e);
    bool bounced = false;
    double apex = 0.0, last_vz = 0.0;
    for (int i = 0; i < 720; ++i) {
      sim.Step();
      const RigidBody& b = *sim.world.Find(id);
      const double vz = b.LinearVelocity().z();
      if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
      if (bounced) {
        apex = std::max(apex, b.x.z() - r);
        if (vz < 0.0) break;
      }
      last_vz = vz;
    }
    EXPECT_NEAR(apex, e * e * h, 0.05 * e * e * h) << "e = " << e;
    std::printf("xpbd: e = %.1f rebound %.5f m, analytic %.5f m (%+.2f%%)\n", e, apex, e * e * h,
                100.0 * (apex - e * e * h) / (e * e * h));
  }
}

// Verifies compliance: with alpha (m/N) per contact, each of a resting box's
// four corners carries m g / 4 and sinks alpha m g / 4 (the XPBD constraint
// is a spring of stiffness 1 / alpha).
TEST(XpbdMethod, ComplianceSinksABoxByItsSpringDeflection) {
  const double alpha = 1e-6, half = 0.1;
  Sim sim("xpbd", {{"compliance", "1e-6"}});
  AddGround(sim.world, 0.0, 0.5);
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, 0.5);
  for (int i = 0; i < 480; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  const double expected = alpha * b.mass * kG / 4.0;
  EXPECT_NEAR(half - b.x.z(), expected, 0.02 * expected);
}

// Verifies that a sphere at 50 m/s does not pass through a 2 cm static box:
// the detection margin grows with the pair's closing speed.
TEST(XpbdMethod, FastSphereDoesNotTunnelThroughThinBox) {
  Sim sim("xpbd");
  sim.world.gravity.setZero();
  BodySettings wall;
  wall.shape = ShapeType::kBox;
  wall.half_extents = Vec3(0.01, 1.0, 1.0);
  wall.fixed = true;
  wall.restitution = 0.0;
  AddValidBody(sim.world, wall);
  const double r = 0.05;
  const BodyId ball = AddSphere(sim.world, r, Vec3(-1.0, 0, 0), 0.0, 0.5, Vec3(50.0, 0, 0));
  for (int i = 0; i < 60; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(ball);
  EXPECT_LT(b.x.x(), -0.01 - r + 1e-6);
  EXPECT_LT(b.LinearVelocity().x(), 1e-6);
}

// Verifies that a tumbling box lands without passing into what it lands
// on: 0.2 m boxes spinning at ~20 rad/s (0.08 rad a step) drop at 2 m/s onto
// a tilted fixed box, from eight orientations. Contacts are found once a
// step (xpbd_method.h), so a corner that turns down within a step is found
// at the next detection: no overlap may be deeper than a corner travels in
// one step, (v + |w| r) dt with r the half diagonal (22 mm; measured 3 mm),
// and the box ends at rest on top, overlapping less than 0.1 mm.
TEST(XpbdMethod, TumblingBoxLandsWithinOneStepOfTravel) {
  const double v = 2.0, dt = 1.0 / 240.0;
  double deepest = 0.0, travel = 0.0;
  for (int k = 0; k < 8; ++k) {
    Sim sim("xpbd");
    BodySettings base;
    base.shape = ShapeType::kBox;
    base.half_extents = Vec3::Constant(0.1);
    const Quat tilt(Eigen::AngleAxisd(0.3 + 0.2 * k, Vec3(1, 2, 3).normalized()));
    base.orientation = Eigen::Vector4d(tilt.w(), tilt.x(), tilt.y(), tilt.z());
    base.fixed = true;
    AddValidBody(sim.world, base);
    const BodyId id = AddBox(sim.world, 0.1, Vec3(0.03 * (k % 3), -0.02 * (k % 2), 0.45), 0.0, 0.5);
    RigidBody& b = *sim.world.Find(id);
    b.q = Quat(Eigen::AngleAxisd(0.7 * k, Vec3(3, -1, 2).normalized()));
    const Vec3 w(10.0 - 2.0 * k, -15.0 + 3.0 * k, 5.0);
    b.SetVelocity(Vec3(0, 0, -v), w);
    travel = std::max(travel, (v + w.norm() * 0.1 * std::sqrt(3.0)) * dt);
    for (int i = 0; i < 60; ++i) {
      sim.Step();
      deepest = std::min(deepest, testing::SmallestGap(sim.world));
    }
    for (int i = 0; i < 480; ++i) sim.Step();
    EXPECT_GT(testing::SmallestGap(sim.world), -1e-4) << k;
  }
  std::printf("deepest overlap of the tumbling boxes %.3g mm (one step's travel %.3g mm)\n", -deepest * 1e3,
              travel * 1e3);
  EXPECT_GT(deepest, -travel);
}

// Verifies that ten 1 m cubes (1,000 kg each, mu 0.5) stacked exactly on the
// ground stand for 10 s: the top moves less than 0.1 mm and the stack keeps
// no kinetic energy. Before xpbd swept its blocks from the highest down and
// held each patch's friction from the step's start (xpbd_contact.h), this
// stack rocked from round-off after ~190 steps and fell (346 J after 10 s).
TEST(XpbdMethod, TenHeavyCubesStandTenSeconds) {
  Sim sim("xpbd");
  AddGround(sim.world, 0.0, 0.5);
  BodyId top = 0;
  for (int i = 0; i < 10; ++i) top = AddBox(sim.world, 0.5, Vec3(0, 0, 0.5 + i), 0.0, 0.5);
  const Vec3 x0 = sim.world.Find(top)->x;
  for (int i = 0; i < 2400; ++i) sim.Step();
  const double moved = (sim.world.Find(top)->x - x0).norm();
  std::printf("ten 1 m cubes: top moved %.3g m, kinetic energy %.3g J\n", moved, KineticEnergy(sim.world));
  EXPECT_LT(moved, 1e-4);
  EXPECT_LT(KineticEnergy(sim.world), 1e-6);
}

// Verifies that the sub-steps grow with the mass ratio of the bodies in
// contact so that a heavy box rests no deeper in a light one than
// kMassRatioOverlap (0.45 mm; one sweep a sub-step leaves the heavy body
// about r g h^2 deep): n = dt sqrt(r g / 0.45 mm), the default 12 below
// about 1:380, 20 at 1:1000; its top ends less than 0.5 mm below its start
// and no overlap passes 1 mm on the way. (At 1:4000, 39 sub-steps, it still
// sinks 7.5 mm in 1 s, docs/methods/xpbd.md.)
TEST(XpbdMethod, SubstepsGrowWithTheMassRatioInContact) {
  for (const double ratio : {1.0, 100.0, 1000.0}) {
    Sim sim("xpbd");
    AddGround(sim.world, 0.0, 0.5);
    BodySettings light;
    light.shape = ShapeType::kBox;
    light.half_extents = Vec3(0.15, 0.15, 0.05);
    light.position = Vec3(0, 0, 0.05);
    light.mass = 0.02;
    AddValidBody(sim.world, light);
    BodySettings heavy = light;
    heavy.position = Vec3(0, 0, 0.15);
    heavy.mass = 0.02 * ratio;
    const BodyId top = AddValidBody(sim.world, heavy);
    StepStats stats;
    double deepest = 0.0;
    for (int i = 0; i < 240; ++i) {
      stats = sim.Step();
      deepest = std::max(deepest, stats.max_penetration);
    }
    const double expected = std::max(static_cast<double>(XpbdParams().substeps), std::ceil(sim.world.dt * std::sqrt(ratio * kG / 0.45e-3)));
    std::printf("1:%-5g %d sub-steps, deepest %.3g mm, top %.3g mm below its start\n", ratio, stats.substeps,
                deepest * 1e3, (0.15 - sim.world.Find(top)->x.z()) * 1e3);
    EXPECT_EQ(stats.substeps, static_cast<int>(expected)) << ratio;
    EXPECT_LT(0.15 - sim.world.Find(top)->x.z(), 0.5e-3) << ratio;
    EXPECT_LT(deepest, 1e-3) << ratio;
  }
}

// Verifies that a body without contacts moves exactly as every method moves
// it: the whole step at once by AdvanceBallistic (the solve leaves it alone).
TEST(XpbdMethod, FreeFlightMatchesTheBallisticStep) {
  Sim sim("xpbd", {{"substeps", "4"}});
  const BodyId id = AddBox(sim.world, Vec3(0.1, 0.2, 0.4), Vec3(0, 0, 5), 0.5, 0.5, Vec3(1, 2, 3));
  sim.world.Find(id)->SetVelocity(Vec3(1, 2, 3), Vec3(3, -1, 2));
  World reference = sim.world;
  for (int i = 0; i < 24; ++i) {
    sim.Step();
    reference.AccumulateForces();
    for (RigidBody& body : reference.bodies()) AdvanceBallistic(body, reference.dt);
    reference.FinishStep();
  }
  EXPECT_EQ(HashWorldState(sim.world), HashWorldState(reference));
}

// Verifies parameter validation: a bad value is named and changes nothing.
TEST(XpbdMethod, RejectsBadParametersAndKeepsTheOldOnes) {
  XpbdMethod m;
  const Status st = m.SetParams({{"substeps", "8"}, {"compliance", "-1"}});
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("compliance"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("-1"), std::string::npos) << st.message();
  EXPECT_EQ(m.params().substeps, XpbdParams().substeps);
  EXPECT_TRUE(m.SetParams({{"substeps", "8"}, {"iterations", "2"}}).ok());
  EXPECT_EQ(m.Params().at("substeps"), "8");
  EXPECT_EQ(m.Params().at("iterations"), "2");
}

}  // namespace
}  // namespace contactsim
