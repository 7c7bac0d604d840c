// Joints and contacts in one lcp problem (both solvers): statically
// determinate scenes in which the contact forces follow from the joint's
// reaction (moments about a hinge, a rod's tension), so that the contact
// rows' impulses are right only when the joint rows are in the same solve
// and that solve is converged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/contact/joint_test_util.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::AddHinge;
using testing::AddJoint;
using testing::AddSphere;
using testing::AddValidBody;
using testing::JointSim;
using testing::kG;

// Sum over the step's contacts between bodies `a` and `b` (ids, either
// order) of the normal values and of the tangential values.
struct PairForce {
  double normal = 0.0;
  Vec3 tangent = Vec3::Zero();
};
PairForce ContactSum(const ContactSet& contacts, BodyId a, BodyId b) {
  PairForce f;
  for (const Contact& c : contacts) {
    if ((c.id_a == a && c.id_b == b) || (c.id_a == b && c.id_b == a)) {
      f.normal += c.normal_value;
      f.tangent += c.tangent_value;
    }
  }
  return f;
}

class LcpJointContactTest : public ::testing::TestWithParam<const char*> {
 protected:
  std::string Spec() const { return std::string("lcp:") + GetParam(); }
};

// Verifies that a plank hinged at one end (a door lying flat) and resting
// on the ridge of a box turned 45 degrees carries its weight by moments:
// with no friction the ridge pushes straight up, N x_ridge = m g x_cm about
// the hinge, so N = m g x_cm / x_ridge (here 5/8 m g) and the hinge takes
// the rest. The ridge force, averaged over the last second of 3 s, is within
// 1%; the plank stays level (to the contact slop over its length) and still.
TEST_P(LcpJointContactTest, HingedPlankOnARidgeSplitsItsWeightByMoments) {
  JointSim sim(Spec());
  const Vec3 pivot(0, 0, 1);
  const double half_len = 0.5, half_thick = 0.02, x_ridge = 0.8;
  const BodyId plank = AddBox(sim.world, Vec3(half_len, 0.1, half_thick), pivot + Vec3(half_len, 0, 0), 0.0, 0.0);
  AddHinge(sim.world, plank, kWorldBody, pivot, Vec3::UnitY());
  BodySettings ridge;
  ridge.shape = ShapeType::kBox;
  ridge.half_extents = Vec3(0.1, 0.3, 0.1);
  ridge.fixed = true;
  ridge.friction = 0.0;
  const double half_diagonal = 0.1 * std::sqrt(2.0);
  ridge.position = Vec3(x_ridge, 0, pivot.z() - half_thick - half_diagonal);
  ridge.orientation = Eigen::Vector4d(std::cos(kPi / 8), 0, std::sin(kPi / 8), 0);  // 45 degrees about y
  const BodyId support = AddValidBody(sim.world, ridge);

  const double m = sim.world.Find(plank)->mass;
  const double expected = m * kG * half_len / x_ridge;  // N
  double impulse = 0.0, time = 0.0, tilt = 0.0, speed = 0.0;
  while (sim.world.time < 3.0) {
    sim.Step();
    const RigidBody& p = *sim.world.Find(plank);
    tilt = std::max(tilt, std::abs((p.q * Vec3::UnitX()).z()));
    if (sim.world.time <= 2.0) continue;
    impulse += ContactSum(sim.contacts, plank, support).normal;
    time += sim.world.dt;
    speed = std::max(speed, p.AngularVelocity().norm());
  }
  const double force = impulse / time;
  std::printf("[%s] ridge force %.5f N, m g x_cm / x_ridge %.5f N, error %.2e; tilt %.2e, spin %.2e rad/s\n",
              GetParam(), force, expected, force / expected - 1.0, tilt, speed);
  EXPECT_NEAR(force / expected, 1.0, 0.01);
  EXPECT_LT(tilt, 2e-3 / x_ridge);  // the plank sinks at most about the slop into the ridge
  EXPECT_LT(speed, 1e-3);
}

// Verifies that a pendulum bob held out at theta by a frictionless box
// (standing on a rough floor) rests in the equilibrium of three forces:
// rod tension T along the rod, weight m g, and the wall's push N along the
// face normal; T cos(theta) = m g and T sin(theta) = N give
// N = m g tan(theta). The box in turn stands by floor friction equal to N
// and floor normal forces summing to its own weight (the wall force is
// horizontal). Forces averaged over the last second of 3 s, within 1%; the
// bob and the box stay put.
TEST_P(LcpJointContactTest, PendulumLeaningOnABoxPushesWithMgTanTheta) {
  JointSim sim(Spec());
  const Vec3 pivot(0, 0, 1.2);
  const double l = 1.0, theta = 0.3, r = 0.05, half = 0.2;
  const BodyId floor = AddGround(sim.world, 0.0, 0.8);
  const Vec3 bob_start = pivot + l * Vec3(std::sin(theta), 0, -std::cos(theta));
  const BodyId bob = AddSphere(sim.world, r, bob_start, 0.0, 0.0);
  AddJoint(sim.world, JointKind::kDistance, bob, kWorldBody, pivot);
  const Vec3 box_start(bob_start.x() - r - half, 0, half);
  const BodyId box = AddBox(sim.world, half, box_start, 0.0, 0.8);

  const double m = sim.world.Find(bob)->mass, M = sim.world.Find(box)->mass;
  const double wall_expected = m * kG * std::tan(theta);  // N
  double wall = 0.0, floor_n = 0.0, time = 0.0, moved = 0.0;
  Vec3 floor_t = Vec3::Zero();
  while (sim.world.time < 3.0) {
    sim.Step();
    moved = std::max({moved, (sim.world.Find(bob)->x - bob_start).norm(), (sim.world.Find(box)->x - box_start).norm()});
    if (sim.world.time <= 2.0) continue;
    wall += ContactSum(sim.contacts, bob, box).normal;
    const PairForce f = ContactSum(sim.contacts, floor, box);
    floor_n += f.normal;
    floor_t += f.tangent;
    time += sim.world.dt;
  }
  wall /= time;
  floor_n /= time;
  const double friction = floor_t.norm() / time;
  std::printf("[%s] wall %.5f N (m g tan theta %.5f, error %.1e), floor friction %.5f N (error %.1e), floor "
              "normal %.3f N (M g %.3f), moved %.2e m\n", GetParam(), wall, wall_expected, wall / wall_expected - 1.0,
              friction, friction / wall_expected - 1.0, floor_n, M * kG, moved);
  EXPECT_NEAR(wall / wall_expected, 1.0, 0.01);
  EXPECT_NEAR(friction / wall_expected, 1.0, 0.01);
  EXPECT_NEAR(floor_n / (M * kG), 1.0, 0.01);
  EXPECT_LT(moved, 2e-3);  // within the contact slop
}

INSTANTIATE_TEST_SUITE_P(Solvers, LcpJointContactTest, ::testing::Values("pgs", "lemke"));

}  // namespace
}  // namespace contactsim
