// Tests of rigid-body integration against analytic results.
#include "service/physics/integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "service/physics/body_settings.h"

namespace contactsim {
namespace {

constexpr double kDt = 1.0 / 240.0;  // s, the default step

RigidBody MakeBox(const Vec3& half, const Vec3& w) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = half;
  s.angular_velocity = w;
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return b;
}

void StepFree(World& world, double dt) {
  world.AccumulateForces();
  IntegrateMomenta(world, dt);
  IntegratePositions(world, dt);
  world.FinishStep();
}

// Verifies free flight under gravity: velocity is exact (v0 + g t) and the
// semi-implicit Euler position has its known O(dt) offset,
// x_n = x0 + v0 t + g dt^2 n (n + 1) / 2.
TEST(Integrator, FreeFlightMatchesTheDiscreteSolution) {
  World world;
  BodySettings s;
  s.radius = 0.1;
  s.linear_velocity = Vec3(1.0, 0.0, 5.0);
  RigidBody b;
  ASSERT_TRUE(CreateBody(s, Material{}, &b).ok());
  const BodyId id = world.AddBody(b);
  const int n = 480;
  for (int i = 0; i < n; ++i) StepFree(world, kDt);
  const RigidBody& r = *world.Find(id);
  const double t = n * kDt;
  EXPECT_NEAR(r.LinearVelocity().z(), 5.0 - 9.81 * t, 1e-12);
  EXPECT_NEAR(r.x.x(), 1.0 * t, 1e-12);
  EXPECT_NEAR(r.x.z(), 5.0 * t - 9.81 * kDt * kDt * n * (n + 1) / 2.0, 1e-10);
}

// Verifies that AdvanceBallistic is exact under constant force:
// x = x0 + v0 h + g h^2 / 2 for any h.
TEST(Integrator, BallisticAdvanceIsExactUnderConstantForce) {
  World world;
  BodySettings s;
  s.radius = 0.1;
  s.linear_velocity = Vec3(0.0, 2.0, 3.0);
  RigidBody b;
  ASSERT_TRUE(CreateBody(s, Material{}, &b).ok());
  world.AddBody(b);
  world.AccumulateForces();
  RigidBody& r = world.bodies()[0];
  AdvanceBallistic(r, 0.37);
  EXPECT_NEAR(r.x.z(), 3.0 * 0.37 - 0.5 * 9.81 * 0.37 * 0.37, 1e-14);
  EXPECT_NEAR(r.x.y(), 2.0 * 0.37, 1e-14);
  EXPECT_NEAR(r.LinearVelocity().z(), 3.0 - 9.81 * 0.37, 1e-13);
}

// Verifies that a torque-free asymmetric body keeps |L| to 1e-9 relative and
// its kinetic energy within 1e-3 relative over 10,000 steps.
TEST(Integrator, TorqueFreeBodyConservesAngularMomentumAndEnergy) {
  World world;
  world.gravity.setZero();
  const BodyId id = world.AddBody(MakeBox(Vec3(0.1, 0.2, 0.4), Vec3(1.0, 3.0, 0.5)));
  const double l0 = world.Find(id)->L.norm();
  const double e0 = world.Find(id)->KineticEnergy();
  double worst_energy = 0.0;
  for (int i = 0; i < 10000; ++i) {
    StepFree(world, kDt);
    worst_energy = std::max(worst_energy, std::abs(world.Find(id)->KineticEnergy() - e0) / e0);
  }
  EXPECT_NEAR(world.Find(id)->L.norm(), l0, 1e-9 * l0);
  EXPECT_LT(worst_energy, 1e-3);
  std::printf("torque-free box, 10,000 steps: max relative energy drift %.3e\n", worst_energy);
}

// Body-frame angular velocity component along body axis k.
double BodyAxisRate(const RigidBody& b, int k) { return (b.q.conjugate() * b.AngularVelocity())[k]; }

// Verifies the intermediate-axis theorem (Dzhanibekov effect): spin about the
// intermediate principal axis flips, spin about the major or minor axis stays.
TEST(Integrator, IntermediateAxisSpinFlipsWhileMajorAndMinorStay) {
  // half extents (0.1, 0.2, 0.4): I_x > I_y > I_z, so y is the intermediate axis
  const Vec3 half(0.1, 0.2, 0.4);
  for (int axis = 0; axis < 3; ++axis) {
    World world;
    world.gravity.setZero();
    Vec3 w = Vec3::Constant(0.01);  // small perturbation
    w[axis] = 5.0;
    const BodyId id = world.AddBody(MakeBox(half, w));
    double min_rate = 1e9;
    for (int i = 0; i < 4800; ++i) {  // 20 s
      StepFree(world, kDt);
      min_rate = std::min(min_rate, BodyAxisRate(*world.Find(id), axis));
    }
    if (axis == 1) {
      EXPECT_LT(min_rate, -4.0) << "intermediate axis did not flip";
    } else {
      EXPECT_GT(min_rate, 4.9) << "axis " << axis << " is stable but drifted";
    }
  }
}

}  // namespace
}  // namespace contactsim
