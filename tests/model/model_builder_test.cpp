// Tests of the model builder and adder on hand-made descriptions: poses at
// q = 0, joint axes and limits, merged links' mass properties, the checks
// and the all-or-nothing load.
#include "service/model/model_builder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "service/model/body_plan.h"
#include "service/model/model_adder.h"
#include "service/physics/cylinder_hull.h"
#include "tests/model/hand_made_models.h"

namespace contactsim::model {
namespace {

using testing::Arm;
using testing::Revolute;
using testing::SphereLink;


// Verifies that every body sits at its link's pose at q = 0 composed from
// the base pose and the joint origins, and that the hinges carry the
// file's axes (turned into the world) and limits.
TEST(ModelBuilderTest, PosesAxesAndLimitsAtZero) {
  ModelOptions o;
  o.base.position = Vec3(1, 2, 3);
  o.base.orientation = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));
  ModelBuild b;
  ASSERT_TRUE(BuildModel(Arm(), o, &b).ok());
  ASSERT_EQ(b.bodies.size(), 3u);
  ASSERT_EQ(b.joints.size(), 2u);
  const Mat3 R = o.base.orientation.toRotationMatrix();
  const Vec3 upper = Vec3(1, 2, 3) + R * Vec3(0, 0, 0.5);
  const Vec3 fore = upper + R * Vec3(0.4, 0, 0);
  EXPECT_LT((b.link_pose_W[1].position - upper).norm(), 1e-15);
  EXPECT_LT((b.link_pose_W[2].position - fore).norm(), 1e-15);
  // the forearm's body is given in its link frame, with its centre of mass
  // (0.2, 0, 0) in that frame and its sphere there
  EXPECT_LT((b.bodies[2].settings.position - fore).norm(), 1e-15);
  ASSERT_TRUE(b.bodies[2].settings.center_of_mass.has_value());
  EXPECT_LT((*b.bodies[2].settings.center_of_mass - Vec3(0.2, 0, 0)).norm(), 1e-15);
  ASSERT_EQ(b.bodies[2].settings.parts.size(), 1u);
  EXPECT_LT((b.bodies[2].settings.parts[0].position - Vec3(0.2, 0, 0)).norm(), 1e-15);
  EXPECT_LT((*b.joints[0].settings.axis - R * Vec3::UnitY()).norm(), 1e-15);
  EXPECT_LT((*b.joints[1].settings.axis - R * Vec3::UnitZ()).norm(), 1e-15);
  EXPECT_LT((b.joints[1].settings.anchor - fore).norm(), 1e-15);
  ASSERT_TRUE(b.joints[0].settings.limits.has_value());
  EXPECT_EQ(b.joints[0].settings.limits->first, -1.0);
  EXPECT_EQ(b.joints[0].settings.limits->second, 2.0);
  EXPECT_EQ(b.record.joints[0].effort_limit, 10.0);
  EXPECT_EQ(b.record.joints[0].velocity_limit, 3.0);
  EXPECT_EQ(b.record.joints[0].type, "revolute");
}

// Verifies that a model goes into the world whole: its bodies with the
// file's masses, its joints between the right bodies, the record's link
// frames, and that REMOVE takes all of it out again.
TEST(ModelBuilderTest, AddsAndRemovesAsAWhole) {
  World world;
  RigidBody ground;
  ground.shape = Shape::Sphere(1.0);
  ground.MakeStatic();
  world.AddBody(ground);
  ModelOptions o;
  o.fixed_base = true;
  ModelBuild b;
  ASSERT_TRUE(BuildModel(Arm(), o, &b).ok());
  PreparedModel p;
  ASSERT_TRUE(PrepareModel(b, world, Material(), &p).ok());
  ModelRecord r;
  ASSERT_TRUE(CommitModel(std::move(p), &world, &r).ok());
  ASSERT_EQ(world.bodies().size(), 4u);
  ASSERT_EQ(world.joints().size(), 2u);
  EXPECT_EQ(r.id, 1);
  EXPECT_EQ(r.links[0].body, 2);
  EXPECT_FALSE(world.Find(2)->IsDynamic());  // the fixed base
  EXPECT_DOUBLE_EQ(world.Find(3)->mass, 1.0);
  EXPECT_DOUBLE_EQ(world.Find(4)->mass, 0.5);
  EXPECT_EQ(world.joints()[0].body_a, 2);
  EXPECT_EQ(world.joints()[0].body_b, 3);
  EXPECT_EQ(r.joints[1].joint, world.joints()[1].id);
  // the upper arm's body sits at its centre of mass, 0.1 m along the link's x
  EXPECT_LT((r.links[1].position - Vec3(-0.1, 0, 0)).norm(), 1e-15);
  ModelRecord second;
  ModelBuild again;
  ASSERT_TRUE(BuildModel(Arm(), o, &again).ok());
  const Status dup = PrepareModel(again, world, Material(), &p);
  EXPECT_EQ(dup.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(dup.message().find("named \"arm\""), std::string::npos) << dup.message();
  ModelRecord removed;
  ASSERT_TRUE(RemoveModel(r.id, &world, &removed).ok());
  EXPECT_EQ(world.bodies().size(), 1u);
  EXPECT_TRUE(world.joints().empty());
  EXPECT_TRUE(world.models.empty());
  EXPECT_EQ(RemoveModel(r.id, &world, &removed).code(), StatusCode::kNotFound);
}

// Verifies that each moving joint's actuator takes the file's effort and
// velocity limits with no torque or gains (it drives nothing), that 0 or
// no <limit> leaves it unlimited, and that the world's joints get them.
TEST(ModelBuilderTest, ActuatorsTakeTheFilesEffortAndVelocityLimits) {
  ModelDescription d = Arm();
  d.joints[1].limits->effort = 0.0;  // none given
  ModelBuild b;
  ASSERT_TRUE(BuildModel(d, ModelOptions(), &b).ok());
  ASSERT_EQ(b.joints.size(), 2u);
  EXPECT_EQ(b.joints[0].actuator.effort_limit, 10.0);
  EXPECT_EQ(b.joints[0].actuator.velocity_limit, 3.0);
  EXPECT_FALSE(IsActuated(b.joints[0].actuator));
  EXPECT_TRUE(std::isinf(b.joints[1].actuator.effort_limit));
  EXPECT_EQ(b.joints[1].actuator.velocity_limit, 3.0);
  d.joints[1].limits.reset();
  d.joints[1].type = JointType::kContinuous;
  ASSERT_TRUE(BuildModel(d, ModelOptions(), &b).ok());
  EXPECT_TRUE(std::isinf(b.joints[1].actuator.effort_limit));
  EXPECT_TRUE(std::isinf(b.joints[1].actuator.velocity_limit));
  World world;
  PreparedModel p;
  ASSERT_TRUE(PrepareModel(b, world, Material(), &p).ok());
  ModelRecord r;
  ASSERT_TRUE(CommitModel(std::move(p), &world, &r).ok());
  ASSERT_EQ(world.joints().size(), 2u);
  EXPECT_EQ(world.joints()[0].actuator.effort_limit, 10.0);
  EXPECT_EQ(world.joints()[0].actuator.velocity_limit, 3.0);
  EXPECT_EQ(world.joints()[0].actuator.kp, 0.0);
  EXPECT_TRUE(std::isinf(world.joints()[1].actuator.velocity_limit));
}

// Verifies that a bad joint in the middle of the file refuses the whole
// model with an error that names the model and the joint.
TEST(ModelBuilderTest, BadJointInTheMiddleRefusesAll) {
  struct Case {
    const char* what;
    void (*spoil)(ModelJoint*);
    const char* expect;
  };
  const Case cases[] = {
      {"unknown child", [](ModelJoint* j) { j->child = "nowhere"; }, "child link 'nowhere' is not in the model"},
      {"unknown parent", [](ModelJoint* j) { j->parent = "nowhere"; }, "parent link 'nowhere' is not in the model"},
      {"zero axis", [](ModelJoint* j) { j->axis = Vec3::Zero(); }, "axis"},
      {"limits out of order", [](ModelJoint* j) { j->limits->lower = 3.0; }, "is above upper"},
      {"negative damping", [](ModelJoint* j) { j->damping = -1.0; }, "damping"},
      {"planar", [](ModelJoint* j) { j->type = JointType::kPlanar; }, "planar"},
      {"loop", [](ModelJoint* j) { j->child = "base"; }, "loop"},
  };
  for (const Case& c : cases) {
    ModelDescription d = Arm();
    d.links.push_back(SphereLink("hand", 0.2, 0.03, Vec3::Zero()));
    d.joints.push_back(Revolute("wrist", "fore", "hand", Vec3(0.3, 0, 0), Vec3::UnitX()));
    std::swap(d.joints[1], d.joints[2]);  // the spoiled joint stands between two good ones
    c.spoil(&d.joints[1]);
    ModelBuild b;
    const Status st = BuildModel(d, ModelOptions(), &b);
    EXPECT_FALSE(st.ok()) << c.what;
    EXPECT_NE(st.message().find("model \"arm\""), std::string::npos) << st.message();
    EXPECT_NE(st.message().find(c.expect), std::string::npos) << c.what << ": " << st.message();
    EXPECT_TRUE(b.bodies.empty()) << c.what;
  }
}

// Verifies that masses and inertias no rigid body can have are refused by
// link name: zero and negative mass, a non-positive-definite inertia, one
// that breaks the triangle inequality, and two roots.
TEST(ModelBuilderTest, RefusesImpossibleLinks) {
  auto refused = [](ModelDescription d, const char* expect) {
    ModelBuild b;
    const Status st = BuildModel(d, ModelOptions(), &b);
    EXPECT_FALSE(st.ok());
    EXPECT_NE(st.message().find(expect), std::string::npos) << st.message();
  };
  ModelDescription d = Arm();
  d.links[1].inertial->mass = 0.0;
  refused(d, "link 'upper'");
  refused(d, "mass is 0 kg; a link's mass must be positive");
  d = Arm();
  d.links[1].inertial->mass = -2.0;
  refused(d, "mass is -2 kg");
  d = Arm();
  d.links[2].inertial->inertia = Vec3(1, 1, -1).asDiagonal();
  refused(d, "inertia is not positive definite");
  d = Arm();
  d.links[2].inertial->inertia = Vec3(1, 1, 3).asDiagonal();
  refused(d, "triangle inequality");
  d = Arm();
  d.joints.pop_back();
  refused(d, "2 root links");
  d = Arm();
  d.links.clear();
  refused(d, "the model has no links");
}

// Verifies the mass properties of links merged by fixed joints against
// the parallel axis theorem worked by hand: two links of diagonal inertia
// whose centres lie 0.2 m apart on x, the second turned 90 degrees about z.
TEST(ModelBuilderTest, MergesFixedLinksExactly) {
  ModelDescription d;
  d.name = "weld";
  d.source = "<inline>";
  Link a, c;
  a.name = "a";
  a.inertial = Inertial{1.0, Pose(), Vec3(0.1, 0.2, 0.3).asDiagonal()};
  c.name = "c";
  c.inertial = Inertial{3.0, Pose(), Vec3(0.4, 0.5, 0.6).asDiagonal()};
  d.links = {a, c};
  ModelJoint j;
  j.name = "weld";
  j.type = JointType::kFixed;
  j.parent = "a";
  j.child = "c";
  j.origin.position = Vec3(0.2, 0, 0);
  j.origin.orientation = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  d.joints = {j};
  ModelTree tree;
  ASSERT_TRUE(CheckModel(&d, &tree).ok());
  std::vector<BodyPlan> plans;
  std::vector<int> link_body;
  std::vector<Pose> link_in_body;
  PlanBodies(d, tree, &plans, &link_body, &link_in_body);
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_EQ(link_body, (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(plans[0].mass, 4.0);
  EXPECT_LT((plans[0].com - Vec3(0.15, 0, 0)).norm(), 1e-15);
  // c's inertia turned about z swaps its x and y moments; each mass lies
  // on x at 0.15 and 0.05 m from the centre: m d^2 adds 0.0225 + 0.0075 to y and z
  const Mat3 expect = Vec3(0.1 + 0.5, 0.2 + 0.4 + 0.03, 0.3 + 0.6 + 0.03).asDiagonal();
  EXPECT_LT((plans[0].inertia - expect).cwiseAbs().maxCoeff(), 1e-14) << plans[0].inertia;
}

// Verifies that a link's file mass properties reach the body exactly: an
// off-centre centre of mass and an inertia with products of inertia in a
// turned inertial frame, on a link of two collision elements (a compound),
// one of them a cylinder (a hull of two 71-gons).
TEST(ModelBuilderTest, LinkMassPropertiesAreExact) {
  ModelDescription d = Arm();
  Link& upper = d.links[1];
  upper.inertial->origin.position = Vec3(0.01, 0.02, 0.15);
  upper.inertial->origin.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  upper.inertial->inertia << 0.02, 0.001, -0.002, 0.001, 0.03, 0.0015, -0.002, 0.0015, 0.015;
  CollisionElement shaft;
  shaft.origin.position = Vec3(0, 0, 0.15);
  shaft.geometry.type = GeometryType::kCylinder;
  shaft.geometry.radius = 0.05;
  shaft.geometry.length = 0.3;
  upper.collisions.push_back(shaft);
  World world;
  ModelBuild b;
  ASSERT_TRUE(BuildModel(d, ModelOptions(), &b).ok());
  ASSERT_EQ(b.bodies[1].settings.parts.size(), 2u);
  EXPECT_EQ(b.bodies[1].settings.parts[1].type, ShapeType::kConvex);
  EXPECT_EQ(b.bodies[1].settings.parts[1].points.size(), 2u * CylinderSides());
  PreparedModel p;
  ASSERT_TRUE(PrepareModel(b, world, Material(), &p).ok());
  ModelRecord r;
  ASSERT_TRUE(CommitModel(std::move(p), &world, &r).ok());
  const RigidBody& body = *world.Find(r.links[1].body);
  const Mat3 R = upper.inertial->origin.orientation.toRotationMatrix();
  const Mat3 expect = R * upper.inertial->inertia * R.transpose();  // about the centre, in the link's axes
  EXPECT_DOUBLE_EQ(body.mass, 1.0);
  EXPECT_LT((body.inertia_body - expect).cwiseAbs().maxCoeff(), 1e-15) << body.inertia_body;
  EXPECT_LT((body.x - (Vec3(0, 0, 0.5) + Vec3(0.01, 0.02, 0.15))).norm(), 1e-15);
  EXPECT_LT((r.links[1].position + Vec3(0.01, 0.02, 0.15)).norm(), 1e-15);
}

// Verifies the joints the engine gained for models: a prismatic joint with
// its limits, damping and friction, and that self-collision off puts every
// body of a model in its own negative collision group (on: no group).
TEST(ModelBuilderTest, PrismaticJointsAndSelfCollisionGroups) {
  ModelDescription d = Arm();
  d.joints[1].type = JointType::kPrismatic;
  d.joints[1].limits = JointLimits{-0.1, 0.2, 5.0, 1.0};
  d.joints[1].damping = 0.5;
  d.joints[1].friction = 0.25;
  World world;
  for (bool self_collide : {false, true}) {
    ModelOptions o;
    o.self_collide = self_collide;
    o.name = self_collide ? "with" : "without";
    ModelBuild b;
    ASSERT_TRUE(BuildModel(d, o, &b).ok());
    const JointSettings& s = b.joints[1].settings;
    EXPECT_EQ(s.kind, JointKind::kPrismatic);
    EXPECT_EQ(*s.limits, std::make_pair(-0.1, 0.2));
    EXPECT_EQ(s.damping, 0.5);
    EXPECT_EQ(s.friction, 0.25);
    EXPECT_FALSE(s.collide_connected);
    PreparedModel p;
    ASSERT_TRUE(PrepareModel(b, world, Material(), &p).ok());
    ModelRecord r;
    ASSERT_TRUE(CommitModel(std::move(p), &world, &r).ok());
    for (const ModelLinkEntry& l : r.links) {
      EXPECT_EQ(world.Find(l.body)->collision_group, self_collide ? 0 : -r.id) << l.name;
    }
  }
}

// Verifies PyBullet's default for a link without <inertial> that is a body
// of its own (1 kg, unit inertia at the link origin), and that a massless
// link welded to a massive one adds nothing.
TEST(ModelBuilderTest, MasslessLinks) {
  ModelDescription d = Arm();
  d.links[2].inertial.reset();
  Link tool;
  tool.name = "tool";
  d.links.push_back(tool);
  ModelJoint weld;
  weld.name = "tool_weld";
  weld.type = JointType::kFixed;
  weld.parent = "upper";
  weld.child = "tool";
  d.joints.push_back(weld);
  ModelBuild b;
  ASSERT_TRUE(BuildModel(d, ModelOptions(), &b).ok());
  ASSERT_EQ(b.bodies.size(), 3u);
  EXPECT_EQ(*b.bodies[2].settings.mass, kDefaultLinkMass);
  EXPECT_EQ(*b.bodies[2].settings.inertia, Mat3::Identity());
  EXPECT_EQ(*b.bodies[1].settings.mass, 1.0);  // upper, with the massless tool welded on
  EXPECT_EQ(b.link_body[3], 1);
}

// Verifies that a mesh link's hull takes at most the options' vertex budget
// of the mesh's points (the default 64, or another), that 0 keeps every
// hull vertex, and that a budget below four is refused naming the model.
TEST(ModelBuilderTest, MeshHullsKeepTheVertexBudget) {
  ModelDescription d = Arm();
  Geometry& g = d.links[2].collisions[0].geometry;
  g.type = GeometryType::kMesh;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < 300; ++i) {  // 300 points on a sphere of 4 cm: every one a hull vertex
    const double z = 1.0 - 2.0 * (i + 0.5) / 300;
    const double r = std::sqrt(1.0 - z * z);
    g.mesh_vertices.push_back(0.04 * Vec3(r * std::cos(golden * i), r * std::sin(golden * i), z));
  }
  for (int budget : {kDefaultMaxHullVertices, 16, 0}) {
    ModelOptions o;
    o.max_hull_vertices = budget;
    ModelBuild b;
    ASSERT_TRUE(BuildModel(d, o, &b).ok()) << budget;
    const std::vector<Vec3>& points = b.bodies[2].settings.parts[0].points;
    EXPECT_EQ(static_cast<int>(points.size()), budget == 0 ? 300 : budget) << budget;
  }
  ModelOptions bad;
  bad.max_hull_vertices = 3;
  ModelBuild b;
  const Status st = BuildModel(d, bad, &b);
  EXPECT_EQ(st.message(), "model \"arm\" (<inline>): max_hull_vertices must be 0 (every vertex) or at least 4, got 3");
}

}  // namespace
}  // namespace contactsim::model
