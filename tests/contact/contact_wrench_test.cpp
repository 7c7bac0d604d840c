// Contact sensors' readings (contact_wrench.h) in every registered method,
// checked by Newton's second law on each body: the contact wrench it
// received in a step plus its weight is m a, with a its change of velocity
// over the step. A box resting on the ground reads m g up; the bottom box of
// a stack of two reads 2 m g from the ground and m g down from the top box;
// a box sliding with mu = 0.5 reads friction mu m g against its motion. A
// method that does not report friction forces is refused a contact sensor
// by its contract. dt = 1/240 s; tolerance: the method's resting_force
// (tests/contact/scenario_tolerances.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "service/contact/contact_wrench.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::MethodConfig;
using Sim = testing::MethodSim;

class ContactWrenchTest : public ::testing::TestWithParam<MethodConfig> {
 protected:
  // True (and the test verified) when the method refuses contact sensors.
  bool Refused() {
    const Status st = CheckMethodAcceptsContactSensor(GetParam().method);
    EXPECT_EQ(st.ok(), testing::ContractOf(GetParam()).contact_forces) << st.message();
    if (st.ok()) return false;
    EXPECT_EQ(st.code(), StatusCode::kFailedPrecondition);
    EXPECT_NE(st.message().find("does not report contact forces"), std::string::npos) << st.message();
    return true;
  }
};

BodyId AddCube(Sim& sim, double mass, const Vec3& p, const Vec3& v = Vec3::Zero()) {
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(0.1);
  box.mass = mass;
  box.position = p;
  box.linear_velocity = v;
  box.restitution = 0.0;
  box.friction = 0.5;
  return testing::AddValidBody(sim.world, box);
}

ContactWrench WrenchOf(const Sim& sim, BodyId id) {
  return SumContactWrenches(sim.world, {id}, sim.contacts, sim.method->ValueKind())[0];
}

// The worst residual of Newton's law |F + m g - m dv/dt| over `steps` steps,
// relative to m g, for each body of `ids`.
double WorstNewtonResidual(Sim& sim, const std::vector<BodyId>& ids, int steps) {
  double worst = 0.0;
  for (int s = 0; s < steps; ++s) {
    std::vector<Vec3> v0;
    for (BodyId id : ids) v0.push_back(sim.world.Find(id)->LinearVelocity());
    sim.Step();
    const std::vector<ContactWrench> w = SumContactWrenches(sim.world, ids, sim.contacts, sim.method->ValueKind());
    for (size_t i = 0; i < ids.size(); ++i) {
      const RigidBody& b = *sim.world.Find(ids[i]);
      const Vec3 ma = b.mass * (b.LinearVelocity() - v0[i]) / sim.world.dt;
      const Vec3 residual = w[i].normal_force + w[i].friction_force + b.mass * sim.world.gravity - ma;
      worst = std::max(worst, residual.norm() / (b.mass * kG));
    }
  }
  return worst;
}

// Verifies a resting box of 0.1, 1 and 10 kg reads m g up, no friction and
// no torque, averaged over a second after a second of settling, and that
// every step obeys Newton's law.
TEST_P(ContactWrenchTest, RestingBoxReadsItsWeight) {
  if (Refused()) return;
  const double tol = testing::TolerancesOf(GetParam().label).resting_force;
  for (double mass : {0.1, 1.0, 10.0}) {
    Sim sim(GetParam().method, GetParam().params);
    testing::AddGround(sim.world, 0.0, 0.5);
    const BodyId id = AddCube(sim, mass, Vec3(0, 0, 0.1));
    while (sim.world.time < 1.0) sim.Step();
    Vec3 normal = Vec3::Zero(), friction = Vec3::Zero(), torque = Vec3::Zero();
    const int steps = 240;
    for (int s = 0; s < steps; ++s) {
      sim.Step();
      const ContactWrench w = WrenchOf(sim, id);
      EXPECT_GT(w.contacts, 0);
      normal += w.normal_force / steps;
      friction += w.friction_force / steps;
      torque += w.torque / steps;
    }
    const double weight = mass * kG;
    std::printf("%-10s %5.1f kg: normal %.6f m g, friction %.2e, torque %.2e N m\n", GetParam().label.c_str(), mass,
                normal.z() / weight, friction.norm(), torque.norm());
    EXPECT_NEAR(normal.z() / weight, 1.0, tol) << mass;
    EXPECT_NEAR(normal.head<2>().norm() / weight, 0.0, tol);
    EXPECT_NEAR(friction.norm() / weight, 0.0, tol);
    EXPECT_NEAR(torque.norm() / (weight * 0.1), 0.0, tol);
    const double residual = WorstNewtonResidual(sim, {id}, 60);
    std::printf("%-10s %5.1f kg: worst |F + m g - m dv/dt| %.2e m g\n", GetParam().label.c_str(), mass, residual);
    EXPECT_LT(residual, tol) << mass;
  }
}

// Verifies the stack of two: the bottom box's ground contacts carry 2 m g,
// its net reading is m g (the top box presses down with m g), the top box
// reads m g.
TEST_P(ContactWrenchTest, StackOfTwoReadsByNewtonsLaw) {
  if (Refused()) return;
  const double tol = testing::TolerancesOf(GetParam().label).resting_force;
  const double mass = 1.0, weight = mass * kG;
  Sim sim(GetParam().method, GetParam().params);
  const BodyId ground = testing::AddGround(sim.world, 0.0, 0.5);
  const BodyId bottom = AddCube(sim, mass, Vec3(0, 0, 0.1));
  const BodyId top = AddCube(sim, mass, Vec3(0, 0, 0.3));
  while (sim.world.time < 1.0) sim.Step();
  double from_ground = 0.0, bottom_net = 0.0, top_net = 0.0;
  const int steps = 240;
  for (int s = 0; s < steps; ++s) {
    sim.Step();
    ContactSet ground_contacts;
    for (const Contact& c : sim.contacts) {
      if (c.id_a == ground || c.id_b == ground) ground_contacts.push_back(c);
    }
    from_ground += SumContactWrenches(sim.world, {bottom}, ground_contacts, sim.method->ValueKind())[0]
                       .normal_force.z() / steps;
    const std::vector<ContactWrench> w =
        SumContactWrenches(sim.world, {bottom, top}, sim.contacts, sim.method->ValueKind());
    bottom_net += w[0].normal_force.z() / steps;
    top_net += w[1].normal_force.z() / steps;
  }
  std::printf("%-10s stack: ground %.6f m g, bottom %.6f m g, top %.6f m g\n", GetParam().label.c_str(),
              from_ground / weight, bottom_net / weight, top_net / weight);
  EXPECT_NEAR(from_ground / weight, 2.0, 2 * tol);
  EXPECT_NEAR(bottom_net / weight, 1.0, 2 * tol);
  EXPECT_NEAR(top_net / weight, 1.0, tol);
  const double residual = WorstNewtonResidual(sim, {bottom, top}, 60);
  std::printf("%-10s stack: worst |F + m g - m dv/dt| %.2e m g\n", GetParam().label.c_str(), residual);
  EXPECT_LT(residual, 2 * tol);
}

// Verifies a box sliding at 2 m/s reads friction mu m g against its motion
// while it slides, and that each step obeys Newton's law.
TEST_P(ContactWrenchTest, SlidingBoxReadsCoulombFriction) {
  if (Refused()) return;
  const double tol = testing::TolerancesOf(GetParam().label).resting_force;
  const double mass = 2.0, weight = mass * kG;
  Sim sim(GetParam().method, GetParam().params);
  testing::AddGround(sim.world, 0.0, 0.5);
  const BodyId id = AddCube(sim, mass, Vec3(0, 0, 0.1), Vec3(2.0, 0, 0));
  for (int s = 0; s < 12; ++s) sim.Step();  // the contact forms
  double friction = 0.0;
  const int steps = 48;  // 0.2 s: still sliding (it stops after 2 / (0.5 g) = 0.41 s)
  for (int s = 0; s < steps; ++s) {
    sim.Step();
    friction += WrenchOf(sim, id).friction_force.x() / steps;
  }
  std::printf("%-10s sliding: friction %.6f m g\n", GetParam().label.c_str(), friction / weight);
  EXPECT_NEAR(friction / weight, -0.5, 0.5 * tol + 0.01);
  const double residual = WorstNewtonResidual(sim, {id}, 24);
  std::printf("%-10s sliding: worst |F + m g - m dv/dt| %.2e m g\n", GetParam().label.c_str(), residual);
  EXPECT_LT(residual, tol + 0.01);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, ContactWrenchTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

// Verifies the wrench's torque about the centre of mass on a hand-made
// contact: 10 N up at 0.1 m along x of a body at the origin is 1 N m about -y.
TEST(ContactWrenchSum, TorqueIsAboutTheCentreOfMass) {
  World world;
  RigidBody a, b;
  b.x = Vec3(0, 0, 0.5);
  const BodyId ia = world.AddBody(a), ib = world.AddBody(b);
  Contact c;
  c.id_a = ia;
  c.id_b = ib;
  c.normal = Vec3::UnitZ();
  c.point = Vec3(0.1, 0, 0.4);
  c.normal_value = 10.0;
  c.tangent_value = Vec3(1, 0, 0);
  const std::vector<ContactWrench> w = SumContactWrenches(world, {ib, ia, 99}, {c}, ContactValueKind::kForce);
  EXPECT_EQ(w[0].normal_force, Vec3(0, 0, 10));
  EXPECT_EQ(w[0].friction_force, Vec3(1, 0, 0));
  EXPECT_NEAR((w[0].torque - Vec3(0.1, 0, -0.1).cross(Vec3(1, 0, 10))).norm(), 0.0, 1e-15);
  EXPECT_EQ(w[1].normal_force, Vec3(0, 0, -10));
  EXPECT_EQ(w[2].contacts, 0);
}

}  // namespace
}  // namespace contactsim
