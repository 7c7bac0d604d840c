// Tests of the joint rows and solvers (contact/joints/): the tree solver
// against the dense one, the rows against finite differences of C, and
// chains, hinges and welds through the contact methods.
#include "service/contact/joints/joint_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "service/contact/joints/joint_dense_solver.h"
#include "service/contact/joints/joint_tree_solver.h"
#include "tests/contact/joint_test_util.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddHangingChain;
using testing::AddHinge;
using testing::AddJoint;
using testing::JointSim;
using testing::kG;

Vec3 RandomVec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3{u(rng), u(rng), u(rng)};
}

// A random tree of n boxes with random sizes, poses and velocities: body i
// is joined to a random earlier body, or (first body, and 10% of the others)
// to the world, by a joint of a random kind. Then n/5 distinct bodies held
// by a ball or distance joint get a second, distance, joint to the world, so
// that trees hold the world at several bodies; that leaves every row
// independent (the system stays regular). Joints are made at the current
// poses, then the bodies are moved a little, so C != 0.
void BuildRandomTree(World& world, int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<BodyId> ids;
  for (int i = 0; i < n; ++i) {
    const Vec3 half{0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng), 0.05 + 0.3 * u(rng)};
    ids.push_back(AddBox(world, half, RandomVec(rng, 3.0), 0.0, 0.5));
    RigidBody& b = *world.Find(ids.back());
    b.q = QuatFromRotationVector(RandomVec(rng, 3.0));
    b.SetVelocity(RandomVec(rng, 2.0), RandomVec(rng, 2.0));
  }
  const JointKind kinds[] = {JointKind::kDistance, JointKind::kBall, JointKind::kHinge, JointKind::kFixed};
  auto join = [&](BodyId a, BodyId b, JointKind kind) {
    JointSettings s;
    s.kind = kind;
    s.body_a = a;
    s.body_b = b;
    s.anchor = world.Find(a)->x + RandomVec(rng, 0.5);
    if (s.kind == JointKind::kHinge) s.axis = RandomVec(rng, 1.0);
    JointId id;
    ASSERT_TRUE(world.AddJoint(s, &id).ok());
  };
  std::vector<bool> loose(n, false);  // held to a body by a ball or distance joint
  for (int i = 0; i < n; ++i) {
    const JointKind kind = kinds[rng() % 4];
    const bool to_world = i == 0 || u(rng) < 0.1;
    join(ids[i], to_world ? kWorldBody : ids[rng() % i], kind);
    loose[i] = !to_world && (kind == JointKind::kBall || kind == JointKind::kDistance);
  }
  for (int i = 0, extra = 0; i < n && extra < n / 5; ++i) {
    if (loose[i]) join(ids[i], kWorldBody, JointKind::kDistance), ++extra;
  }
  for (BodyId id : ids) {
    RigidBody& b = *world.Find(id);
    b.x += RandomVec(rng, 0.01);
    b.q = (QuatFromRotationVector(RandomVec(rng, 0.01)) * b.q).normalized();
  }
}

// The velocity rows of a world and their right-hand side b = rhs - J qdot.
struct VelocitySystem {
  explicit VelocitySystem(const World& world) {
    LoadSolverBodies(world, &bodies);
    AppendJointRows(world, bodies, world.dt, JointRowMode::kVelocity, &rows, &blocks);
    b.resize(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) b[k] = rows[k].rhs - rows[k].Velocity(bodies);
  }
  std::vector<SolverBody> bodies;
  std::vector<ConstraintRow> rows;
  std::vector<JointBlock> blocks;
  Eigen::VectorXd b;
};

// Verifies that SetJointVelocityProducts gives each geometry row the rhs
// AppendJointRows gives it at the same poses and the new velocities, bit
// for bit, and leaves the other rows' targets, on 20 random trees of every
// joint kind whose velocities are then changed.
TEST(JointSolverTest, VelocityProductsInPlaceEqualRowsBuiltAgain) {
  std::mt19937 rng(777);
  for (int trial = 0; trial < 20; ++trial) {
    World world;
    BuildRandomTree(world, 1 + trial, rng);
    VelocitySystem sys(world);
    std::vector<SolverBody> moved = sys.bodies;
    for (SolverBody& s : moved) s.v = RandomVec(rng, 2.0), s.w = RandomVec(rng, 2.0);
    std::vector<ConstraintRow> fresh;
    AppendJointRows(world, moved, world.dt, JointRowMode::kVelocity, &fresh);
    std::vector<ConstraintRow> in_place = sys.rows;
    SetJointVelocityProducts(world, moved, world.dt, sys.blocks, &in_place);
    ASSERT_EQ(fresh.size(), in_place.size());
    for (size_t k = 0; k < fresh.size(); ++k) {
      const bool geometry = !IsLimitRow(fresh[k]) && !IsJointDynamicsRow(fresh[k]);
      EXPECT_EQ(in_place[k].rhs, geometry ? fresh[k].rhs : sys.rows[k].rhs) << "trial " << trial << " row " << k;
    }
  }
}

// Verifies that the tree solver (Baraff 1996) returns the dense solver's
// multipliers to 1e-9 (relative) on 40 random trees of 1 to 30 bodies with
// every joint kind, joints to the world included.
TEST(JointSolverTest, TreeSolverEqualsDenseSolverOnRandomTrees) {
  std::mt19937 rng(12345);
  double worst = 0.0;
  for (int trial = 0; trial < 40; ++trial) {
    World world;
    BuildRandomTree(world, 1 + trial % 30, rng);
    const VelocitySystem sys(world);
    ASSERT_TRUE(JointGraphIsTree(sys.blocks, sys.bodies));
    Eigen::VectorXd tree;
    ASSERT_TRUE(SolveJointsTree(sys.rows, sys.blocks, sys.bodies, sys.b, &tree));
    const Eigen::VectorXd dense = SolveJointsDense(sys.rows, sys.bodies, sys.b);
    worst = std::max(worst, (tree - dense).norm() / dense.norm());
    // and the answer solves the system (backward error, relative to |A| |lambda|)
    const Eigen::MatrixXd A = JointSystemMatrix(sys.rows, sys.bodies);
    EXPECT_LT((A * tree - sys.b).norm(), 1e-12 * A.norm() * tree.norm()) << "trial " << trial;
  }
  std::printf("tree vs dense: largest relative difference %.3e\n", worst);
  EXPECT_LT(worst, 1e-9);
}

// Verifies that a loop (a square of four bodies joined in a ring) is
// detected, and that the solve falls back to the dense solver for it.
TEST(JointSolverTest, LoopsFallBackToTheDenseSolver) {
  World world;
  std::vector<BodyId> ids;
  for (int i = 0; i < 4; ++i) ids.push_back(AddBox(world, 0.1, Vec3(i % 2, i / 2, 1), 0.0, 0.5));
  AddJoint(world, JointKind::kBall, ids[0], ids[1], Vec3(0.5, 0, 1));
  AddJoint(world, JointKind::kBall, ids[1], ids[3], Vec3(1, 0.5, 1));
  AddJoint(world, JointKind::kBall, ids[3], ids[2], Vec3(0.5, 1, 1));
  AddJoint(world, JointKind::kDistance, ids[2], ids[0], Vec3(0, 0, 1));
  world.Find(ids[0])->SetVelocity(Vec3(0, 0, 1), Vec3(0, 1, 0));
  const VelocitySystem sys(world);
  EXPECT_FALSE(JointGraphIsTree(sys.blocks, sys.bodies));
  Eigen::VectorXd lambda;
  EXPECT_FALSE(SolveJointsTree(sys.rows, sys.blocks, sys.bodies, sys.b, &lambda));
  const Eigen::VectorXd dense = SolveJointsDense(sys.rows, sys.bodies, sys.b);
  lambda = SolveJointSystem(sys.rows, sys.blocks, sys.bodies, sys.b, JointSolverKind::kTree);
  EXPECT_LT((lambda - dense).norm(), 1e-12 * dense.norm());
}

// Verifies that every velocity row is the gradient of its error C: for a
// small displacement along random body velocities, C changes by J qdot dt
// (finite differences, to first order).
TEST(JointSolverTest, RowsAreTheGradientsOfTheirErrors) {
  std::mt19937 rng(7);
  World world;
  BuildRandomTree(world, 12, rng);
  const double dt = 1e-7;
  std::vector<SolverBody> bodies;
  LoadSolverBodies(world, &bodies);
  std::vector<ConstraintRow> rows;
  std::vector<double> c0, c1;
  AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &rows, nullptr, &c0);
  for (size_t i = 0; i < bodies.size(); ++i) {
    RigidBody& b = world.bodies()[i];
    b.x += bodies[i].v * dt;
    b.q = (QuatFromRotationVector(bodies[i].w * dt) * b.q).normalized();
  }
  std::vector<ConstraintRow> moved;
  AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &moved, nullptr, &c1);
  ASSERT_EQ(c0.size(), c1.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const double rate = (c1[k] - c0[k]) / dt;
    // first order in the misalignment: the built-in poses are off by 0.01
    EXPECT_NEAR(rate, rows[k].Velocity(bodies), 0.03 * (1.0 + std::abs(rate))) << "row " << k;
  }
}

class JointChainTest : public ::testing::TestWithParam<const char*> {};

// Verifies that a chain of 20 capsules hanging from a ball joint stays at
// rest for 10 s: no link moves by 1e-6 m or reaches 1e-6 m/s (no creeping).
TEST_P(JointChainTest, TwentyLinkChainHangsAtRest) {
  JointSim sim(GetParam());
  const Vec3 top(0, 0, 5);
  const std::vector<BodyId> links = testing::AddHangingChain(sim.world, 20, top, 0.02, 0.06);
  std::vector<Vec3> start;
  for (BodyId id : links) start.push_back(sim.world.Find(id)->x);
  double moved = 0.0, speed = 0.0;
  while (sim.world.time < 10.0) {
    sim.Step();
    for (size_t i = 0; i < links.size(); ++i) {
      const RigidBody& b = *sim.world.Find(links[i]);
      moved = std::max(moved, (b.x - start[i]).norm());
      speed = std::max(speed, b.LinearVelocity().norm() + b.AngularVelocity().norm() * 0.08);
    }
  }
  std::printf("[%s] 20-link chain over 10 s: largest displacement %.3e m, speed %.3e m/s\n", GetParam(), moved,
              speed);
  EXPECT_LT(moved, 1e-6);
  EXPECT_LT(speed, 1e-6);
}

// Verifies that a swinging hinged box, started with a spin off its axis,
// keeps its axis (the box axis that was along the hinge stays along it to
// 1e-9 rad), that its anchor stays on the
// pivot, and that the hinge limits hold to 1e-6 rad while the box swings
// down against the lower limit and comes to rest on it.
TEST_P(JointChainTest, HingeKeepsItsAxisAndLimitsHold) {
  JointSim sim(GetParam());
  const Vec3 pivot(0, 0, 3);
  const double lower = -0.6, upper = 0.2;
  // a box sticking out along +x from a hinge about +y: gravity turns it
  // about +y, which is a negative angle of the world (B) relative to the box
  // (A), so it falls onto the lower limit
  const BodyId box = AddBox(sim.world, Vec3(0.3, 0.05, 0.05), pivot + Vec3(0.3, 0, 0), 0.0, 0.5);
  const JointId hinge = AddHinge(sim.world, box, kWorldBody, pivot, Vec3::UnitY(), std::make_pair(lower, upper));
  sim.world.Find(box)->SetVelocity(Vec3::Zero(), Vec3(1.0, -0.5, 0.7));  // off-axis spin: removed at once
  double worst_axis = 0.0, lowest = 1.0, over = 0.0, anchor = 0.0;
  while (sim.world.time < 5.0) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(box);
    const Joint& j = *sim.world.FindJoint(hinge);
    worst_axis = std::max(worst_axis, (b.q * Vec3::UnitY()).cross(Vec3::UnitY()).norm());
    const double angle = HingeAngle(j, b, nullptr);
    lowest = std::min(lowest, angle);
    over = std::max({over, angle - upper, lower - angle});
    anchor = std::max(anchor, (AnchorWorld(j.anchor_a, &b) - pivot).norm());
  }
  const double final_angle = HingeAngle(*sim.world.FindJoint(hinge), *sim.world.Find(box), nullptr);
  std::printf("[%s] hinge: axis error %.3e rad, anchor error %.3e m, lowest angle %.6f, overshoot %.3e rad, "
              "final %.6f\n", GetParam(), worst_axis, anchor, lowest, over, final_angle);
  EXPECT_LT(worst_axis, 1e-9);
  EXPECT_LT(anchor, 1e-9);
  EXPECT_LT(over, 1e-6);
  EXPECT_LT(lowest, lower + 1e-3);  // it reached the lower limit
  EXPECT_NEAR(final_angle, lower, 1e-6);  // and rests on it (plastic limit)
}

// Verifies that two boxes welded by a fixed joint tumble as one rigid body:
// their relative pose stays the creation pose to 1e-9 while the pair flies
// with a spin.
TEST_P(JointChainTest, FixedJointKeepsTheRelativePose) {
  JointSim sim(GetParam());
  const BodyId a = AddBox(sim.world, Vec3(0.2, 0.1, 0.1), Vec3(0, 0, 10), 0.0, 0.5);
  const BodyId b = AddBox(sim.world, Vec3(0.1, 0.1, 0.3), Vec3(0.3, 0, 10.2), 0.0, 0.5);
  AddJoint(sim.world, JointKind::kFixed, a, b, Vec3(0.2, 0, 10.1));
  sim.world.Find(a)->SetVelocity(Vec3(1, 0, 3), Vec3(2, -1, 3));
  const Quat rel0 = sim.world.Find(a)->q.conjugate() * sim.world.Find(b)->q;
  const Vec3 offset0 = sim.world.Find(b)->x - sim.world.Find(a)->x;
  double worst = 0.0;
  for (int i = 0; i < 240; ++i) {
    sim.Step();
    const RigidBody& A = *sim.world.Find(a);
    const RigidBody& B = *sim.world.Find(b);
    worst = std::max(worst, (A.q.conjugate() * (B.x - A.x) - offset0).norm());
    worst = std::max(worst, (A.q.conjugate() * B.q).angularDistance(rel0));
  }
  EXPECT_LT(worst, 1e-9);
  // the weld carried the spin over to B
  EXPECT_GT(sim.world.Find(b)->AngularVelocity().norm(), 0.5);
}

INSTANTIATE_TEST_SUITE_P(Methods, JointChainTest,
                         ::testing::Values("impulse", "penalty", "lcp:pgs", "lcp:lemke"));

}  // namespace
}  // namespace contactsim
