// Collision filtering (service/physics/collision_filter.h) under every
// registered contact method (method_configs.h): bodies whose masks exclude
// each other pass through each other and still land on the ground; a model
// with its self-collision off (one negative group for its bodies) falls
// through itself but not through another model; a chain whose neighbours
// overlap at their joints reports contacts only between non-neighbours;
// and a filter changed at runtime drops the top box of a resting, sleeping
// stack through the box below it.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "service/contact/sleep/island_sleep.h"
#include "service/physics/collision_filter.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::MethodConfig;

constexpr double kHalf = 0.1;     // m, half size of the boxes
constexpr double kRestBand = 0.01;  // m: a box resting on the ground has its centre within this of kHalf

// A method stepped through the sleep wrapper (sleep on or off).
struct FilterSim : testing::MethodSim {
  IslandSleep sleep;
  explicit FilterSim(const MethodConfig& c, bool sleeping = false) : MethodSim(c.method, c.params) {
    world.sleep.enabled = sleeping;
  }
  void Step() { sleep.Step(world, *method, detector, &contacts); }
  // true when some contact of the last step is between bodies a and b
  bool Touched(BodyId a, BodyId b) const {
    for (const Contact& c : contacts) {
      if ((c.id_a == a && c.id_b == b) || (c.id_a == b && c.id_b == a)) return true;
    }
    return false;
  }
};

// A cube of restitution 0 (every method's contract) with its filter.
BodyId AddFilteredBox(World& world, const Vec3& p, uint32_t category, uint32_t mask, int32_t group) {
  const BodyId id = AddBox(world, kHalf, p, 0.0, 0.5);
  EXPECT_TRUE(world.SetCollisionFilter(id, category, mask, group).ok());
  return id;
}

class CollisionFilterScenarioTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies that two cubes dropped one above the other, each of its own
// category and touching only category 1 (the ground), never report a
// contact with each other and both come to rest on the ground (centres
// within kRestBand of z = half, one inside the other); with the default
// filter the same drop stacks them (the upper one rests at 3 half).
TEST_P(CollisionFilterScenarioTest, BoxesWhoseMasksExcludeEachOtherPassThroughAndLand) {
  for (const bool filtered : {true, false}) {
    FilterSim sim(GetParam());
    AddGround(sim.world, 0.0, 0.5);
    const BodyId lower = AddFilteredBox(sim.world, Vec3(0, 0, kHalf + 0.02), filtered ? 2u : 1u,
                                        filtered ? 1u : 0xFFFFFFFFu, 0);
    const BodyId upper = AddFilteredBox(sim.world, Vec3(0.03, 0, 3 * kHalf + 0.1), filtered ? 4u : 1u,
                                        filtered ? 1u : 0xFFFFFFFFu, 0);
    bool touched = false;
    for (int i = 0; i < 360; ++i) {
      sim.Step();
      touched = touched || sim.Touched(lower, upper);
    }
    const double z_lower = sim.world.Find(lower)->x.z(), z_upper = sim.world.Find(upper)->x.z();
    std::printf("[%s] filtered %d: z %.4f %.4f m\n", GetParam().label.c_str(), filtered, z_lower, z_upper);
    EXPECT_NEAR(z_lower, kHalf, kRestBand);
    EXPECT_NEAR(z_upper, filtered ? kHalf : 3 * kHalf, kRestBand);
    EXPECT_EQ(touched, !filtered);
  }
}

// Verifies the self-collision switch a model builder makes of one negative
// group per model: three cubes of group -1 dropped in a column fall through
// each other to the ground, and a cube of group -2 (another model) dropped
// onto them lands on them (different groups: the masks decide).
TEST_P(CollisionFilterScenarioTest, NegativeGroupFallsThroughItselfButNotThroughAnotherModel) {
  FilterSim sim(GetParam());
  const BodyId ground = AddGround(sim.world, 0.0, 0.5);
  std::vector<BodyId> model;
  for (int i = 0; i < 3; ++i) {
    model.push_back(AddFilteredBox(sim.world, Vec3(0.02 * i, 0, kHalf + 0.01 + 0.25 * i), 1u, 0xFFFFFFFFu, -1));
  }
  const BodyId other = AddFilteredBox(sim.world, Vec3(0, 0, 1.0), 1u, 0xFFFFFFFFu, -2);
  int self_contacts = 0;
  for (int i = 0; i < 480; ++i) {
    sim.Step();
    for (const Contact& c : sim.contacts) {
      const bool a_model = c.id_a != ground && c.id_a != other, b_model = c.id_b != ground && c.id_b != other;
      self_contacts += a_model && b_model;
    }
  }
  EXPECT_EQ(self_contacts, 0);
  for (BodyId id : model) EXPECT_NEAR(sim.world.Find(id)->x.z(), kHalf, kRestBand) << GetParam().label;
  EXPECT_NEAR(sim.world.Find(other)->x.z(), 3 * kHalf, kRestBand) << GetParam().label << ": lands on the model";
  EXPECT_TRUE(sim.Touched(other, model[0]) || sim.Touched(other, model[1]) || sim.Touched(other, model[2]));
}

// Verifies that a hanging chain of five fat capsules on ball joints, each
// overlapping its neighbours at the joints by 8 cm and the link after next
// by 2 cm, reports no contact between neighbours (collide_connected false)
// and contacts between links two apart; with collide_connected true the
// neighbours touch too. A method without joints refuses the chain.
TEST_P(CollisionFilterScenarioTest, ChainReportsContactsOnlyBetweenNonNeighbours) {
  for (const bool connected : {false, true}) {
    FilterSim sim(GetParam());
    const double r = 0.05, hl = 0.02, pitch = 0.06;  // m: a link is 0.14 m tip to tip
    const Vec3 top(0, 0, 2);
    std::vector<BodyId> links;
    for (int i = 0; i < 5; ++i) {
      BodySettings s;
      s.shape = ShapeType::kCapsule;
      s.radius = r;
      s.half_length = hl;
      s.position = top - Vec3(0, 0, (i + 0.5) * pitch);
      s.restitution = 0.0;
      links.push_back(testing::AddValidBody(sim.world, s));
      JointSettings j;
      j.kind = JointKind::kBall;
      j.body_a = links[i];
      j.body_b = i == 0 ? kWorldBody : links[i - 1];
      j.anchor = top - Vec3(0, 0, i * pitch);
      j.collide_connected = connected;
      testing::AddJoint(sim.world, j);
    }
    if (testing::RefusedByContract(GetParam(), sim.world, ContractOf(GetParam()).joints, "joint")) return;
    sim.Step();
    int neighbours = 0, two_apart = 0;
    for (int i = 0; i + 1 < 5; ++i) neighbours += sim.Touched(links[i], links[i + 1]);
    for (int i = 0; i + 2 < 5; ++i) two_apart += sim.Touched(links[i], links[i + 2]);
    std::printf("[%s] collide_connected %d: %d neighbour and %d two-apart pairs touch\n", GetParam().label.c_str(),
                connected, neighbours, two_apart);
    EXPECT_EQ(neighbours, connected ? 4 : 0);
    EXPECT_EQ(two_apart, 3);
  }
}

// Verifies that a filter changed at runtime separates a resting stack:
// two cubes settle (and, with sleep on, fall asleep); the top one's mask is
// then set to the ground's category alone, which wakes the stack, and the
// top cube falls through the lower one onto the ground without another
// contact between them, while the lower one stays where it rests.
TEST_P(CollisionFilterScenarioTest, FilterSetAtRuntimeDropsTheTopOfARestingStack) {
  for (const bool sleeping : {false, true}) {
    FilterSim sim(GetParam(), sleeping);
    AddGround(sim.world, 0.0, 0.5);
    const BodyId lower = AddFilteredBox(sim.world, Vec3(0, 0, kHalf + 1e-3), 2u, 0xFFFFFFFFu, 0);
    const BodyId upper = AddFilteredBox(sim.world, Vec3(0, 0, 3 * kHalf + 2e-3), 1u, 0xFFFFFFFFu, 0);
    for (int i = 0; i < 480; ++i) sim.Step();
    EXPECT_NEAR(sim.world.Find(upper)->x.z(), 3 * kHalf, kRestBand) << "the stack stands";
    const bool slept = sim.world.Find(upper)->asleep();
    ASSERT_TRUE(sim.world.SetCollisionFilter(upper, 1u, 1u, 0).ok());
    EXPECT_FALSE(sim.world.Find(upper)->asleep());
    EXPECT_FALSE(sim.world.Find(lower)->asleep()) << "one island with the top";
    const double z_lower = sim.world.Find(lower)->x.z();
    bool touched = false;
    for (int i = 0; i < 360; ++i) {
      sim.Step();
      touched = touched || sim.Touched(lower, upper);
    }
    std::printf("[%s] sleep %d (asleep before: %d): top at %.4f m\n", GetParam().label.c_str(), sleeping, slept,
                sim.world.Find(upper)->x.z());
    EXPECT_FALSE(touched);
    EXPECT_NEAR(sim.world.Find(upper)->x.z(), kHalf, kRestBand);
    EXPECT_NEAR(sim.world.Find(lower)->x.z(), z_lower, 2e-3);
  }
}

// Verifies that a filtered pair does not join two islands: two cubes
// resting on the ground inside each other (their masks exclude each other)
// fall asleep as two islands, and waking one leaves the other asleep; the
// same cubes unfiltered, one resting on the other, sleep as one island.
TEST_P(CollisionFilterScenarioTest, FilteredPairsSleepAsSeparateIslands) {
  for (const bool filtered : {true, false}) {
    FilterSim sim(GetParam(), true);
    AddGround(sim.world, 0.0, 0.5);
    // inside each other, or stacked
    const Vec3 at_b = filtered ? Vec3(kHalf, 0, kHalf + 1e-3) : Vec3(0, 0, 3 * kHalf + 2e-3);
    const BodyId a = AddFilteredBox(sim.world, Vec3(0, 0, kHalf + 1e-3), 2u, filtered ? 1u : 0xFFFFFFFFu, 0);
    const BodyId b = AddFilteredBox(sim.world, at_b, 4u, filtered ? 1u : 0xFFFFFFFFu, 0);
    for (int i = 0; i < 720 && !(sim.world.Find(a)->asleep() && sim.world.Find(b)->asleep()); ++i) sim.Step();
    ASSERT_TRUE(sim.world.Find(a)->asleep() && sim.world.Find(b)->asleep()) << GetParam().label;
    if (!filtered) {
      EXPECT_EQ(sim.world.Find(a)->sleep_island, sim.world.Find(b)->sleep_island) << "stacked: one island";
      continue;
    }
    EXPECT_NE(sim.world.Find(a)->sleep_island, sim.world.Find(b)->sleep_island);
    sim.world.WakeBody(a);
    sim.Step();
    EXPECT_TRUE(sim.world.Find(b)->asleep()) << "the filtered neighbour's wake box must not wake it";
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, CollisionFilterScenarioTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
