// Tests of the URDF reader: the fixture arm (tests/model/data/arm.urdf)
// against the numbers written in it, and every refusal on a small URDF
// broken one piece at a time.
#include "service/model/urdf_reader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/model/model_test_util.h"

namespace contactsim::model {
namespace {

using testing::DataDir;
using testing::Inertial;
using testing::ReadText;
using testing::TwoLinkUrdf;

// The file's numbers go through urdfdom's text-to-double and its
// rpy-to-quaternion: agreement to a few ulps.
constexpr double kTol = 1e-12;

ModelPaths FixturePaths() { return ModelPaths{{DataDir() + "/models"}}; }

ModelDescription ReadArm() {
  ModelDescription d;
  const std::string path = DataDir() + "/arm.urdf";
  const Status st = ReadUrdf(ReadText(path), path, FixturePaths(), ReadLimits{}, &d);
  EXPECT_TRUE(st.ok()) << st.message();
  return d;
}

Status ReadInline(const std::string& text, ModelDescription* d, const ReadLimits& limits = ReadLimits{}) {
  return ReadUrdf(text, "test.urdf", ModelPaths{}, limits, d);
}

// The status of reading `text`, expected to fail with every piece of `needles` in its message.
void ExpectRefused(const std::string& text, const std::vector<std::string>& needles,
                   const ReadLimits& limits = ReadLimits{}) {
  ModelDescription d;
  d.name = "untouched";
  const Status st = ReadInline(text, &d, limits);
  ASSERT_FALSE(st.ok()) << text;
  for (const std::string& n : needles) EXPECT_NE(st.message().find(n), std::string::npos) << st.message();
  EXPECT_EQ(d.name, "untouched") << "a refused read must leave the description alone";
}

// Verifies that links and joints come in the file's order, not urdfdom's
// name order, and that the root is found.
TEST(UrdfReaderTest, LinksAndJointsKeepTheFilesOrder) {
  const ModelDescription d = ReadArm();
  ASSERT_EQ(d.links.size(), 5u);
  const std::vector<std::string> links = {"base", "upper_arm", "forearm", "wrist", "tool"};
  for (size_t i = 0; i < links.size(); ++i) EXPECT_EQ(d.links[i].name, links[i]);
  ASSERT_EQ(d.joints.size(), 4u);
  const std::vector<std::string> joints = {"shoulder", "elbow", "slide", "tool_mount"};
  for (size_t i = 0; i < joints.size(); ++i) EXPECT_EQ(d.joints[i].name, joints[i]);
  EXPECT_EQ(d.name, "test_arm");
  EXPECT_EQ(d.root_link, "base");
  EXPECT_EQ(d.source, DataDir() + "/arm.urdf");
  EXPECT_FALSE(d.self_collide);
}

// Verifies the inertial: mass, origin with its rpy rotation, and the full
// tensor with products of inertia; a link without <inertial> is massless.
TEST(UrdfReaderTest, InertialIsReadWithProductsAndFrame) {
  const ModelDescription d = ReadArm();
  EXPECT_FALSE(d.links[0].inertial.has_value());
  ASSERT_TRUE(d.links[1].inertial.has_value());
  const model::Inertial& in = *d.links[1].inertial;
  EXPECT_NEAR(in.mass, 2.5, kTol);
  EXPECT_LT((in.origin.position - Vec3(0.01, 0.02, 0.15)).norm(), kTol);
  // URDF rpy: fixed-axis roll about x, then pitch about y, then yaw about z
  const Quat want = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(0.2, Vec3::UnitY())) *
                    Quat(Eigen::AngleAxisd(0.1, Vec3::UnitX()));
  EXPECT_LT(in.origin.orientation.angularDistance(want), kTol);
  Mat3 tensor;
  tensor << 0.02, 0.001, -0.002, 0.001, 0.03, 0.0015, -0.002, 0.0015, 0.015;
  EXPECT_LT((in.inertia - tensor).norm(), kTol);
}

// Verifies every collision and visual: primitives with their sizes and
// origins, several collisions on one link, mesh paths resolved three ways
// (relative, package://, model://) with their scaled vertices, colours.
TEST(UrdfReaderTest, CollisionsAndVisualsAreRead) {
  const ModelDescription d = ReadArm();
  const Link& base = d.links[0];
  ASSERT_EQ(base.collisions.size(), 1u);
  EXPECT_EQ(base.collisions[0].geometry.type, GeometryType::kBox);
  EXPECT_LT((base.collisions[0].geometry.box_size - Vec3(0.2, 0.3, 0.1)).norm(), kTol);
  EXPECT_LT((base.collisions[0].origin.position - Vec3(0, 0, 0.05)).norm(), kTol);
  ASSERT_EQ(base.visuals.size(), 1u);
  EXPECT_LT((base.visuals[0].rgba - Eigen::Vector4d(0.5, 0.5, 0.5, 1)).norm(), kTol);

  const Link& upper = d.links[1];
  ASSERT_EQ(upper.collisions.size(), 2u);
  EXPECT_EQ(upper.collisions[0].name, "shaft");
  EXPECT_EQ(upper.collisions[0].geometry.type, GeometryType::kCylinder);
  EXPECT_NEAR(upper.collisions[0].geometry.radius, 0.05, kTol);
  EXPECT_NEAR(upper.collisions[0].geometry.length, 0.3, kTol);
  EXPECT_EQ(upper.collisions[1].geometry.type, GeometryType::kSphere);
  EXPECT_NEAR(upper.collisions[1].geometry.radius, 0.06, kTol);
  EXPECT_LT((upper.collisions[1].origin.position - Vec3(0, 0, 0.3)).norm(), kTol);
  ASSERT_EQ(upper.visuals.size(), 1u);
  EXPECT_EQ(upper.visuals[0].geometry.type, GeometryType::kMesh);
  EXPECT_EQ(upper.visuals[0].geometry.mesh_path, DataDir() + "/tetra.obj");
  EXPECT_TRUE(upper.visuals[0].geometry.mesh_vertices.empty()) << "a visual mesh is kept as a path";
  // urdfdom keeps colours as floats
  EXPECT_LT((upper.visuals[0].rgba - Eigen::Vector4d(1, 0, 0, 0.8)).norm(), 1e-7);

  const Geometry& cube = d.links[2].collisions.at(0).geometry;
  EXPECT_EQ(cube.mesh_path, DataDir() + "/cube.stl");
  EXPECT_LT((cube.mesh_scale - Vec3(0.1, 0.2, 0.3)).norm(), kTol);
  ASSERT_EQ(cube.mesh_vertices.size(), 8u);
  for (const Vec3& v : cube.mesh_vertices) EXPECT_LT((v.cwiseAbs() - Vec3(0.05, 0.1, 0.15)).norm(), 1e-6);
  EXPECT_EQ(d.links[3].collisions.at(0).geometry.mesh_vertices.size(), 4u);
  EXPECT_EQ(d.links[4].collisions.at(0).geometry.mesh_path, DataDir() + "/models/tetra_model/meshes/tetra.obj");
}

// Verifies joint types, origins, normalised axes, limits and dynamics.
TEST(UrdfReaderTest, JointsAreRead) {
  const ModelDescription d = ReadArm();
  const ModelJoint& shoulder = d.joints[0];
  EXPECT_EQ(shoulder.type, JointType::kRevolute);
  EXPECT_EQ(shoulder.parent, "base");
  EXPECT_EQ(shoulder.child, "upper_arm");
  EXPECT_LT((shoulder.origin.position - Vec3(0, 0, 0.1)).norm(), kTol);
  EXPECT_LT(shoulder.origin.orientation.angularDistance(Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()))), kTol);
  EXPECT_LT((shoulder.axis - Vec3::UnitZ()).norm(), kTol) << "the file's (0 0 2) comes out unit";
  ASSERT_TRUE(shoulder.limits.has_value());
  EXPECT_EQ(shoulder.limits->lower, -1.5);
  EXPECT_EQ(shoulder.limits->upper, 1.5);
  EXPECT_EQ(shoulder.limits->effort, 50.0);
  EXPECT_EQ(shoulder.limits->velocity, 2.0);
  EXPECT_EQ(shoulder.damping, 0.5);
  EXPECT_EQ(shoulder.friction, 0.1);

  EXPECT_EQ(d.joints[1].type, JointType::kContinuous);
  EXPECT_LT((d.joints[1].axis - Vec3::UnitY()).norm(), kTol);
  EXPECT_EQ(d.joints[2].type, JointType::kPrismatic);
  EXPECT_EQ(d.joints[2].limits->upper, 0.2);
  EXPECT_LT(d.joints[2].origin.orientation.angularDistance(Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()))), kTol);
  EXPECT_EQ(d.joints[3].type, JointType::kFixed);
  EXPECT_FALSE(d.joints[3].limits.has_value());
}

// Verifies that floating and planar joints are read, and that an explicit
// zero mass makes a massless link as PyBullet reads it.
TEST(UrdfReaderTest, FloatingPlanarAndZeroMass) {
  ModelDescription d;
  Status st = ReadInline(TwoLinkUrdf(Inertial("0", "ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\""),
                                     "floating", "<parent link=\"a\"/><child link=\"b\"/>"),
                         &d);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(d.joints[0].type, JointType::kFloating);
  EXPECT_FALSE(d.links[1].inertial.has_value());
  st = ReadInline(TwoLinkUrdf("", "planar", "<parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 1\"/>"), &d);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(d.joints[0].type, JointType::kPlanar);
}

const char kGoodInertia[] = "ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"";

// Verifies the refusals of bad numbers: negative mass, NaN mass, NaN
// inertia, NaN origin, an inertia not positive definite, one breaking the
// triangle inequality; each names the file, the link and its line.
TEST(UrdfReaderTest, BadMassAndInertiaAreRefused) {
  ExpectRefused(TwoLinkUrdf(Inertial("-1", kGoodInertia)), {"test.urdf", "link 'b'", "line 4", "mass is -1"});
  ExpectRefused(TwoLinkUrdf(Inertial("nan", kGoodInertia)), {"link 'b' (line 4)", "mass [nan]"});
  ExpectRefused(TwoLinkUrdf(Inertial("1", "ixx=\"nan\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"")),
                {"link 'b'"});
  ExpectRefused(TwoLinkUrdf("<inertial><origin xyz=\"0 nan 0\"/><mass value=\"1\"/><inertia " +
                            std::string(kGoodInertia) + "/></inertial>"),
                {"link 'b'"});
  ExpectRefused(TwoLinkUrdf(Inertial("1", "ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"2\" ixz=\"0\" iyz=\"0\"")),
                {"link 'b'", "not positive definite"});
  ExpectRefused(TwoLinkUrdf(Inertial("1", "ixx=\"1\" iyy=\"1\" izz=\"0\" ixy=\"0\" ixz=\"0\" iyz=\"0\"")),
                {"link 'b'", "not positive definite"});
  ExpectRefused(TwoLinkUrdf(Inertial("1", "ixx=\"1\" iyy=\"1\" izz=\"3\" ixy=\"0\" ixz=\"0\" iyz=\"0\"")),
                {"link 'b'", "triangle inequality"});
}

// Verifies that the triangle inequality has a small relative slack (a thin
// rod's I1 + I2 = I3 printed with rounding) and no more.
TEST(UrdfReaderTest, TriangleInequalityToleranceIsRelative) {
  ModelDescription d;
  EXPECT_TRUE(ReadInline(TwoLinkUrdf(Inertial("1", "ixx=\"1\" iyy=\"1\" izz=\"2.0001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"")), &d)
                  .ok());
  ExpectRefused(TwoLinkUrdf(Inertial("1", "ixx=\"1\" iyy=\"1\" izz=\"2.01\" ixy=\"0\" ixz=\"0\" iyz=\"0\"")),
                {"triangle inequality"});
}

// Verifies the structural refusals: malformed XML with its line, a file
// that is not URDF, an unknown joint type, a joint naming a missing link, a
// link with two parents (a loop), a cycle without a root, two roots, a zero
// axis, a NaN joint origin.
TEST(UrdfReaderTest, BadStructureIsRefused) {
  ExpectRefused("<robot name=\"x\">\n<link name=\"a\">\n</robot>", {"test.urdf", "malformed XML at line"});
  ExpectRefused("<sdf version=\"1.9\"/>", {"not a URDF", "<sdf>"});
  ExpectRefused(TwoLinkUrdf("", "ball"), {"joint 'j'", "line 5", "unknown joint type 'ball'"});
  ExpectRefused(TwoLinkUrdf("", "fixed", "<parent link=\"a\"/><child link=\"c\"/>"),
                {"joint 'j'", "child link 'c' is not in the model"});
  ExpectRefused(TwoLinkUrdf("", "fixed", "<parent link=\"a\"/>"), {"joint 'j'", "no <child"});
  const std::string loop =
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
      "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "<joint name=\"bc\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/></joint>"
      "<joint name=\"ac\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint></robot>";
  ExpectRefused(loop, {"joint 'ac'", "kinematic loop", "already has parent 'b'"});
  const std::string cycle =
      "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/>"
      "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "<joint name=\"ba\" type=\"fixed\"><parent link=\"b\"/><child link=\"a\"/></joint></robot>";
  ExpectRefused(cycle, {"kinematic loop", "a -> b -> a"});
  ExpectRefused("<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/></robot>", {"2 root links", "'a'", "'b'"});
  ExpectRefused("<robot name=\"r\">\n<link name=\"a\"/>\n<link name=\"a\"/>\n</robot>",
                {"link 'a' (line 2)", "a second link of this name (line 3)"});
  ExpectRefused("<robot name=\"r\">\n<link/>\n</robot>", {"a <link> without a name (line 2)"});
  ExpectRefused(TwoLinkUrdf("", "continuous", "<parent link=\"a\"/><child link=\"b\"/><axis xyz=\"0 0 0\"/>"),
                {"joint 'j'", "axis"});
  ExpectRefused(
      TwoLinkUrdf("", "fixed", "<parent link=\"a\"/><child link=\"b\"/><origin xyz=\"0 0 0\" rpy=\"nan 0 0\"/>"),
      {"joint 'j' (line 5)", "[nan]"});
  ExpectRefused(TwoLinkUrdf("", "prismatic",
                            "<parent link=\"a\"/><child link=\"b\"/><limit lower=\"1\" upper=\"0\" effort=\"1\" "
                            "velocity=\"1\"/>"),
                {"joint 'j'", "lower 1 is above upper 0"});
}

// Verifies that a missing collision or visual mesh, an unreadable mesh and
// a capsule (not URDF; urdfdom refuses it) fail with the link named.
TEST(UrdfReaderTest, MissingMeshesAndUnknownGeometryAreRefused) {
  ExpectRefused(TwoLinkUrdf("<collision><geometry><mesh filename=\"gone.stl\"/></geometry></collision>"),
                {"link 'b'", "collision 0", "gone.stl"});
  ExpectRefused(TwoLinkUrdf("<visual><geometry><mesh filename=\"package://nopkg/v.dae\"/></geometry></visual>"),
                {"link 'b'", "visual 0", "package://nopkg/v.dae"});
  ExpectRefused(TwoLinkUrdf("<collision><geometry><capsule radius=\"1\" length=\"1\"/></geometry></collision>"),
                {"link 'b' (line 4)", "Unknown geometry type 'capsule'"});
}

// Verifies the limits: file size, link and joint counts, mesh vertices
// over the whole model.
TEST(UrdfReaderTest, LimitsAreEnforced) {
  ReadLimits limits;
  limits.max_file_bytes = 100;
  ExpectRefused(TwoLinkUrdf(""), {"test.urdf", "max_file_bytes"}, limits);
  limits = ReadLimits{};
  limits.max_links = 1;
  ExpectRefused(TwoLinkUrdf(""), {"2 links", "max_links"}, limits);
  limits = ReadLimits{};
  limits.max_joints = 0;
  ExpectRefused(TwoLinkUrdf(""), {"1 joints", "max_joints"}, limits);
  limits = ReadLimits{};
  limits.max_total_mesh_vertices = 10;
  ModelDescription d;
  const std::string path = DataDir() + "/arm.urdf";
  const Status st = ReadUrdf(ReadText(path), path, FixturePaths(), limits, &d);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("max_total_mesh_vertices"), std::string::npos) << st.message();
}

// Verifies that every cut of the fixture file and every character of it
// turned into a stray one is either read or refused with the file named,
// never a crash (run under the sanitizers in CI).
TEST(UrdfReaderTest, DamagedFilesAreReadOrRefused) {
  const std::string path = DataDir() + "/arm.urdf";
  const std::string text = ReadText(path);
  size_t refused = 0, tried = 0;
  auto attempt = [&](const std::string& damaged) {
    ModelDescription d;
    const Status st = ReadUrdf(damaged, path, FixturePaths(), ReadLimits{}, &d);
    ++tried;
    if (!st.ok()) {
      ++refused;
      EXPECT_NE(st.message().find("arm.urdf"), std::string::npos) << st.message();
    }
  };
  for (size_t cut = 0; cut < text.size(); cut += 23) attempt(text.substr(0, cut));
  for (size_t at = 0; at < text.size(); at += 17) {
    for (const char c : {'<', '"', '-', 'x'}) {
      std::string damaged = text;
      damaged[at] = c;
      attempt(damaged);
    }
  }
  EXPECT_GT(refused, tried / 4) << "most damage must be noticed";
}

}  // namespace
}  // namespace contactsim::model
