// Tests of the joints' constrained mobility (contact/joints/joint_mobility.h)
// against closed forms: a weld does not move, a hinge turns about its axis
// with the inertia about that axis, and a chain's responses keep its joints
// and are symmetric (Z_ki = Z_ik^T).
#include "service/contact/joints/joint_mobility.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "service/contact/joints/joint_rows.h"
#include "tests/contact/joint_test_util.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddHinge;
using testing::AddJoint;

Vec6 RandomWrench(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec6 w;
  for (int i = 0; i < 6; ++i) w[i] = u(rng);
  return w;
}

// A 0.4 x 0.2 x 0.1 m box at p, turned a little so that its inertia is not
// diagonal in the world frame.
BodyId AddTurnedBox(World& world, const Vec3& p) {
  const BodyId id = AddBox(world, Vec3(0.2, 0.1, 0.05), p, 0.0, 0.5);
  world.Find(id)->q = QuatFromRotationVector(Vec3(0.3, -0.2, 0.5));
  return id;
}

JointMobility Build(const World& world, const std::vector<char>& wanted) {
  std::vector<SolverBody> bodies;
  LoadSolverBodies(world, &bodies);
  JointMobility mobility;
  mobility.Build(world, bodies, wanted);
  return mobility;
}

// Verifies that a body welded to the world takes no motion from any wrench.
TEST(JointMobilityTest, WeldedBodyDoesNotMove) {
  World world;
  const BodyId box = AddTurnedBox(world, Vec3(0, 0, 1));
  AddJoint(world, JointKind::kFixed, box, kWorldBody, Vec3(0.1, 0, 1));
  const int i = world.IndexOf(box);
  const JointMobility mobility = Build(world, {1});
  ASSERT_TRUE(mobility.Jointed(i));
  // the free response of a 0.4 x 0.2 x 0.1 m box is of order 1 to 300;
  // the joints' regularisation (1e-10 relative) leaves a trace
  EXPECT_LT(mobility.Own(i).cwiseAbs().maxCoeff(), 1e-7);
}

// Verifies that a hinged body turns about its hinge: a wrench (F, tau) at
// the centre of mass x gives omega = a (a . tau_p) / I_a, tau_p = tau +
// (x - p) x F its torque about the pivot p and I_a the inertia about the
// axis through p (parallel axes), and moves x by omega x (x - p).
TEST(JointMobilityTest, HingedBodyTurnsAboutItsHinge) {
  World world;
  const Vec3 pivot(0.3, -0.1, 1.4);
  const Vec3 axis = Vec3(0.2, 1.0, -0.3).normalized();
  const BodyId box = AddTurnedBox(world, Vec3(0, 0, 1));
  AddHinge(world, box, kWorldBody, pivot, axis);
  const int i = world.IndexOf(box);
  const JointMobility mobility = Build(world, {1});
  ASSERT_TRUE(mobility.Jointed(i));
  const RigidBody& b = world.bodies()[i];
  const Vec3 r = b.x - pivot;
  const Mat3 inertia = b.InertiaWorld() + b.mass * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
  const double i_axis = axis.dot(inertia * axis);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const Vec6 w = RandomWrench(rng);
    const Vec3 tau_p = w.tail<3>() + r.cross(w.head<3>());
    const Vec3 omega = axis * (axis.dot(tau_p) / i_axis);
    const Vec6 motion = mobility.Own(i) * w;
    // the joints' regularisation (1e-10 of the rows' diagonal) lets a trace
    // of the free motion M^-1 w through
    const double free = (b.inv_mass * w.head<3>()).norm() + (b.InvInertiaWorld() * w.tail<3>()).norm();
    EXPECT_LT((motion.tail<3>() - omega).norm(), 1e-8 * (omega.norm() + free)) << trial;
    EXPECT_LT((motion.head<3>() - omega.cross(r)).norm(), 1e-8 * (omega.norm() + free)) << trial;
  }
}

// Verifies that in a chain of three boxes hanging from the world (ball,
// hinge, ball) the motion a wrench on the middle box gives every box keeps
// the joints (J dq = 0 to round-off), that the responses are symmetric, and
// that an unjointed body is left out.
TEST(JointMobilityTest, ChainResponsesKeepTheJointsAndAreSymmetric) {
  World world;
  std::vector<BodyId> links;
  for (int k = 0; k < 3; ++k) links.push_back(AddTurnedBox(world, Vec3(0.5 * k, 0, 2.0 - 0.3 * k)));
  const BodyId loose = AddTurnedBox(world, Vec3(3, 0, 1));
  AddJoint(world, JointKind::kBall, links[0], kWorldBody, Vec3(-0.2, 0, 2.1));
  AddHinge(world, links[1], links[0], Vec3(0.25, 0, 1.85), Vec3(0, 1, 0));
  AddJoint(world, JointKind::kBall, links[2], links[1], Vec3(0.75, 0, 1.55));
  const int n = static_cast<int>(world.bodies().size());
  std::vector<char> wanted(n, 1);
  const JointMobility mobility = Build(world, wanted);
  const int mid = world.IndexOf(links[1]), last = world.IndexOf(links[2]);
  EXPECT_FALSE(mobility.Jointed(world.IndexOf(loose)));
  EXPECT_TRUE(mobility.SameComponent(mid, last));
  EXPECT_FALSE(mobility.SameComponent(mid, world.IndexOf(loose)));
  ASSERT_EQ(mobility.end(mid) - mobility.begin(mid), 3);
  EXPECT_EQ(mobility.begin(mid)->body, mid);

  std::vector<SolverBody> bodies;
  LoadSolverBodies(world, &bodies);
  std::vector<ConstraintRow> rows;
  AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &rows);
  std::mt19937 rng(11);
  const Vec6 w = RandomWrench(rng);
  std::vector<SolverBody> moved = bodies;
  double scale = 0.0;
  for (const JointMobility::Response* r = mobility.begin(mid); r != mobility.end(mid); ++r) {
    const Vec6 d = r->z * w;
    moved[r->body].v = d.head<3>();
    moved[r->body].w = d.tail<3>();
    scale = std::max(scale, d.norm());
  }
  for (const ConstraintRow& row : rows) EXPECT_LT(std::abs(row.Velocity(moved)), 1e-9 * scale);

  // Z_{last, mid} (last's motion under a wrench on mid) against Z_{mid, last}^T
  const Mat6* z_last_mid = nullptr;
  const Mat6* z_mid_last = nullptr;
  for (const JointMobility::Response* r = mobility.begin(mid); r != mobility.end(mid); ++r) {
    if (r->body == last) z_last_mid = &r->z;
  }
  for (const JointMobility::Response* r = mobility.begin(last); r != mobility.end(last); ++r) {
    if (r->body == mid) z_mid_last = &r->z;
  }
  ASSERT_TRUE(z_last_mid != nullptr && z_mid_last != nullptr);
  EXPECT_LT((*z_last_mid - z_mid_last->transpose()).cwiseAbs().maxCoeff(), 1e-9 * z_last_mid->cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace contactsim
