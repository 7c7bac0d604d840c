// Tests of the contact methods' contracts (service/contact/method_contract.h,
// declared in the registry's table): each "yes" holds in a scenario with an
// analytic answer, and each "no" is true, which is why the server refuses
// such a world for that method (tests/server/sim_server_contract_test.cpp).
#include "service/contact/method_contract.h"

#include <contactsim/protocol.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "service/contact/contact_method_registry.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::MethodSim;

// Verifies the text STATUS carries: the four capabilities, then friction
// (last, since its words hold spaces).
TEST(MethodContractTest, DescriptionListsCapabilitiesThenFriction) {
  const MethodContract c{true, false, true, "coulomb disk", true, true};
  EXPECT_EQ(DescribeContract(c), "joints=yes; restitution=no; kinematic=yes; contact_forces=yes; friction=coulomb disk");
}

// Verifies that the registry holds exactly the methods the protocol names
// (lcmtypes/protocol.toml), in its order: the clients and the viewer offer
// that list.
TEST(MethodContractTest, TheRegistryHoldsTheProtocolsMethods) {
  const std::vector<std::string> named(std::begin(protocol::kMethodNames), std::end(protocol::kMethodNames));
  EXPECT_EQ(ContactMethodNames(), named);
}

// Verifies that the registry's table gives every method a contract with a
// friction law, and that the names are the table's, in order.
TEST(MethodContractTest, EveryRegisteredMethodDeclaresItsContract) {
  std::vector<std::string> names;
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    names.push_back(e.name);
    EXPECT_GT(std::string(e.contract.friction).size(), 0u) << e.name;
    EXPECT_STREQ(e.create()->Name(), e.name);
  }
  EXPECT_EQ(names, ContactMethodNames());
  EXPECT_EQ(FindContactMethod("nosuch"), nullptr);
}

class MethodContractScenarioTest : public ::testing::TestWithParam<std::string> {
 protected:
  const MethodContract& contract() const { return FindContactMethod(GetParam())->contract; }
};

constexpr double kGap = 0.5e-3;       // m, start gap: barrier pairs must start apart (below its 1 mm d_hat)
constexpr double kHalf = 0.1;         // m, the carried cube's half size
constexpr double kSlabHalf = 0.05;    // m, the platform's half thickness
// m: how far the cube may sit from the platform's top: the methods' own
// resting offsets are impulse's 1 mm slop, penalty's m g / kp, barrier's
// gap below d_hat; 3 mm is three times the largest
constexpr double kRestTolerance = 3e-3;

// A kinematic slab of half size (0.5, 0.5, kSlabHalf) at the origin moving
// at `v`, and a dynamic cube kGap above it; returns the cube's id.
BodyId PlatformWithCube(World& world, const Vec3& v) {
  BodySettings slab;
  slab.shape = ShapeType::kBox;
  slab.half_extents = Vec3(0.5, 0.5, kSlabHalf);
  slab.kinematic = true;
  slab.linear_velocity = v;
  slab.restitution = 0.0;
  testing::AddValidBody(world, slab);
  return testing::AddBox(world, kHalf, Vec3(0, 0, kSlabHalf + kHalf + kGap), 0.0, 0.5);
}

// Verifies the contract's kinematic bodies: a platform rising at 0.2 m/s
// for 1 s keeps its prescribed path, and a method that declares kinematic
// bodies lifts the cube resting on it (neither sinking in nor left
// behind); one that does not (barrier) loses the cube, so the server
// refuses kinematic bodies for it.
TEST_P(MethodContractScenarioTest, KinematicPlatformLiftsACubeExactlyWhenDeclared) {
  MethodSim sim(GetParam());
  const double vz = 0.2;  // m/s
  const BodyId cube = PlatformWithCube(sim.world, Vec3(0, 0, vz));
  const int steps = static_cast<int>(std::lround(1.0 / sim.world.dt));
  for (int i = 0; i < steps; ++i) sim.Step();
  const double top = sim.world.bodies()[0].x.z() + kSlabHalf;
  EXPECT_NEAR(top, kSlabHalf + vz * sim.world.time, 1e-9) << "the platform left its prescribed path";
  const RigidBody& b = *sim.world.Find(cube);
  std::printf("%-8s cube %.4g m above the platform's top\n", GetParam().c_str(), b.x.z() - kHalf - top);
  if (contract().kinematic_bodies) {
    EXPECT_NEAR(b.x.z() - kHalf, top, kRestTolerance) << GetParam();
    EXPECT_NEAR(b.LinearVelocity().z(), vz, 0.02) << GetParam();
  } else {
    EXPECT_GT(std::abs(b.x.z() - kHalf - top), kRestTolerance) << GetParam();
  }
}

// Verifies that a platform sliding at 0.3 m/s carries a cube by friction
// (mu 0.5: the cube reaches the platform's speed within 0.07 s) and the
// cube stays on top.
TEST_P(MethodContractScenarioTest, KinematicPlatformCarriesACubeByFriction) {
  if (!contract().kinematic_bodies) GTEST_SKIP() << GetParam() << " declares no kinematic bodies";
  MethodSim sim(GetParam());
  const double vx = 0.3;  // m/s
  const BodyId cube = PlatformWithCube(sim.world, Vec3(vx, 0, 0));
  const int steps = static_cast<int>(std::lround(1.0 / sim.world.dt));
  for (int i = 0; i < steps; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(cube);
  EXPECT_NEAR(b.LinearVelocity().x(), vx, 0.01) << GetParam();
  EXPECT_NEAR(b.x.z() - kHalf, kSlabHalf, kRestTolerance) << GetParam();
  // behind the platform by the slip v^2 / (2 mu g) = 9 mm at most
  EXPECT_NEAR(b.x.x(), vx * sim.world.time, 0.015) << GetParam();
}

// The highest point the sphere's bottom reaches after its first contact
// with the ground, dropped from 0.9 m with restitution e on both.
double ReboundApex(const std::string& method, const ParamMap& params, double e) {
  MethodSim sim(method, params);
  const double radius = 0.1, drop = 0.9;  // m
  testing::AddGround(sim.world, e, 0.5);
  const BodyId ball = testing::AddSphere(sim.world, radius, Vec3(0, 0, radius + drop), e);
  bool bounced = false;
  double apex = 0.0;
  const int steps = static_cast<int>(std::lround(1.0 / sim.world.dt));  // fall 0.43 s, rise 0.21 s
  for (int i = 0; i < steps; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(ball);
    bounced = bounced || !sim.contacts.empty();
    if (bounced) apex = std::max(apex, b.x.z() - radius);
  }
  return apex;
}

// Verifies the contract's restitution: a method that declares it bounces a
// ball to the analytic e^2 h (within 10%: the methods' thresholds and
// detection margins); one that does not (barrier) keeps less than a tenth of
// it, so a bouncy world would be stepped wrongly, and the server refuses it.
// Penalty runs with a resolved bounce, the settings of
// penalty_method_test.cpp (kp 1e5 N/m, 4 sub-steps, theta = 0.5): at its
// defaults the linearly implicit Euler step (theta = 1, sqrt(kp / m) h = 2)
// damps this bounce to 0.150 m, two thirds of e^2 h (docs/physics.md,
// "Method contract").
TEST_P(MethodContractScenarioTest, RestitutionIsSimulatedExactlyWhenDeclared) {
  const double e = 0.5, expected = e * e * 0.9;  // m
  const ParamMap params = GetParam() == "penalty"
                              ? ParamMap{{"theta", "0.5"}, {"kp", "1e5"}, {"substeps", "4"}}
                              : ParamMap{};
  const double apex = ReboundApex(GetParam(), params, e);
  std::printf("%-8s rebound apex %.4f m (e^2 h = %.4f m)\n", GetParam().c_str(), apex, expected);
  if (contract().restitution) {
    EXPECT_NEAR(apex, expected, 0.1 * expected) << GetParam();
  } else {
    EXPECT_LT(apex, 0.1 * expected) << GetParam();
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MethodContractScenarioTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace contactsim
