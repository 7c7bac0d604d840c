// Tests of Baraff's acceleration-level resting-contact LCP.
#include "service/contact/lcp/resting_contact.h"

#include <gtest/gtest.h>

#include <numeric>

#include "service/collision/collision_detector.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2
// Lemke's polished answer is exact to round-off on these 4x4 and 8x8
// problems (forces of order 1e3 N): 1e-9 relative.
constexpr double kRel = 1e-9;

using testing::AddBox;
using testing::AddGround;

// Net linear and angular acceleration of body `index` under its
// accumulated force and torque plus the contact forces.
void NetAcceleration(const World& world, const ContactSet& contacts, const std::vector<double>& f, int index,
                     Vec3* a, Vec3* alpha) {
  const RigidBody& body = world.bodies()[index];
  Vec3 F = body.force, tau = body.torque;
  for (size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    const double sign = c.b == index ? 1.0 : (c.a == index ? -1.0 : 0.0);
    F += sign * f[i] * c.normal;
    tau += (c.point - body.x).cross(sign * f[i] * c.normal);
  }
  *a = F * body.inv_mass;
  *alpha = body.InvInertiaWorld() * tau;
}

// Verifies that a box resting on the plane gets normal forces summing to
// its weight and has zero linear and angular acceleration.
TEST(RestingContact, BoxOnPlaneCarriesItsWeightWithZeroAcceleration) {
  World world;
  AddGround(world, 0.5, 0.5);
  const BodyId id = AddBox(world, Vec3(0.3, 0.2, 0.1), Vec3(0, 0, 0.1), 0.5, 0.5);
  world.AccumulateForces();
  CollisionDetector detector;
  ContactSet contacts;
  detector.Detect(world, 1e-3, world.dt, &contacts);
  ASSERT_EQ(contacts.size(), 4u);
  RestingContactResult result;
  ASSERT_TRUE(SolveRestingContact(world, contacts, &result).ok());
  const RigidBody& box = *world.Find(id);
  const double weight = box.mass * kG;
  EXPECT_NEAR(std::accumulate(result.forces.begin(), result.forces.end(), 0.0), weight, kRel * weight);
  for (double f : result.forces) EXPECT_GE(f, 0.0);
  Vec3 a, alpha;
  NetAcceleration(world, contacts, result.forces, world.IndexOf(id), &a, &alpha);
  EXPECT_LT(a.norm(), kRel * kG);
  EXPECT_LT(alpha.norm(), kRel * kG);
  EXPECT_LT(result.accelerations.cwiseAbs().maxCoeff(), kRel * kG);
}

// Verifies a two-box stack: the ground carries both weights, the upper
// contacts the upper box's weight, and both boxes have zero acceleration.
TEST(RestingContact, TwoBoxStackCarriesBothWeights) {
  World world;
  AddGround(world, 0.5, 0.5);
  const BodyId lower = AddBox(world, 0.1, Vec3(0, 0, 0.1), 0.5, 0.5);
  const BodyId upper = AddBox(world, 0.1, Vec3(0.05, 0, 0.3), 0.5, 0.5);
  world.AccumulateForces();
  CollisionDetector detector;
  ContactSet contacts;
  detector.Detect(world, 1e-3, world.dt, &contacts);
  RestingContactResult result;
  ASSERT_TRUE(SolveRestingContact(world, contacts, &result).ok());
  const int lo = world.IndexOf(lower), up = world.IndexOf(upper);
  double ground = 0.0, between = 0.0;
  for (size_t i = 0; i < contacts.size(); ++i) {
    const bool on_ground = contacts[i].a != lo && contacts[i].a != up;
    (on_ground ? ground : between) += result.forces[i];
  }
  const double m = world.Find(lower)->mass;
  EXPECT_NEAR(ground, 2.0 * m * kG, kRel * m * kG);
  EXPECT_NEAR(between, m * kG, kRel * m * kG);
  for (int index : {lo, up}) {
    Vec3 a, alpha;
    NetAcceleration(world, contacts, result.forces, index, &a, &alpha);
    EXPECT_LT(a.norm(), 1e-6) << index;
    EXPECT_LT(alpha.norm(), 1e-6) << index;
  }
}

// Verifies that a box lifted by an upward force larger than its weight gets
// no contact force (the contacts separate: ddot(d) > 0, f = 0).
TEST(RestingContact, LiftedBoxGetsNoForce) {
  World world;
  AddGround(world, 0.5, 0.5);
  const BodyId id = AddBox(world, 0.1, Vec3(0, 0, 0.1), 0.5, 0.5);
  const double m = world.Find(id)->mass;
  world.AddWrench({id, Vec3(0, 0, 2.0 * m * kG), Vec3::Zero(), 0.0});
  world.AccumulateForces();
  CollisionDetector detector;
  ContactSet contacts;
  detector.Detect(world, 1e-3, world.dt, &contacts);
  RestingContactResult result;
  ASSERT_TRUE(SolveRestingContact(world, contacts, &result).ok());
  for (double f : result.forces) EXPECT_EQ(f, 0.0);
  for (Eigen::Index i = 0; i < result.accelerations.size(); ++i) EXPECT_NEAR(result.accelerations[i], kG, 1e-9);
}

}  // namespace
}  // namespace contactsim
