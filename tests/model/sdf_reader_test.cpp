// Tests of the SDF reader: the fixture arm (tests/model/data/arm.sdf) with
// its nested gripper against numbers worked out by hand below, and every
// refusal on small inline models.
#include "service/model/sdf_reader.h"

#include <gtest/gtest.h>

#include "tests/model/model_test_util.h"

namespace contactsim::model {
namespace {

using testing::DataDir;
using testing::ReadText;

// Poses go through libsdformat's pose graph and our compositions: a few ulps.
constexpr double kTol = 1e-12;

Quat Yaw(double angle) { return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())); }

void ExpectPose(const Pose& p, const Vec3& position, const Quat& orientation, const std::string& what) {
  EXPECT_LT((p.position - position).norm(), kTol) << what << ": " << p.position.transpose();
  EXPECT_LT(p.orientation.angularDistance(orientation), kTol) << what;
}

ModelDescription ReadArm() {
  ModelDescription d;
  const std::string path = DataDir() + "/arm.sdf";
  const Status st = ReadSdf(ReadText(path), path, ModelPaths{{DataDir() + "/models"}}, ReadLimits{}, &d);
  EXPECT_TRUE(st.ok()) << st.message();
  return d;
}

std::string Model(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<sdf version=\"1.9\">\n<model name=\"m\">\n" + body + "</model>\n</sdf>\n";
}

std::string SimpleLink(const std::string& name, const std::string& extra = "") {
  return "<link name=\"" + name + "\"><inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy><izz>1</izz>"
         "</inertia></inertial>" + extra + "</link>\n";
}

std::string Joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& extra = "<axis><xyz>0 0 1</xyz></axis>") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent>" + parent + "</parent><child>" + child +
         "</child>" + extra + "</joint>\n";
}

void ExpectRefused(const std::string& text, const std::vector<std::string>& needles) {
  ModelDescription d;
  d.name = "untouched";
  const Status st = ReadSdf(text, "test.sdf", ModelPaths{}, ReadLimits{}, &d);
  ASSERT_FALSE(st.ok()) << text;
  for (const std::string& n : needles) EXPECT_NE(st.message().find(n), std::string::npos) << st.message();
  EXPECT_EQ(d.name, "untouched");
}

// Verifies names, order (a model's own links and joints, then its nested
// models', scoped "gripper::"), the root and <self_collide>.
TEST(SdfReaderTest, NestedModelsAreFlattenedWithScopedNames) {
  const ModelDescription d = ReadArm();
  EXPECT_EQ(d.name, "sdf_arm");
  EXPECT_TRUE(d.self_collide);
  EXPECT_EQ(d.root_link, "base");
  ASSERT_EQ(d.links.size(), 4u);
  const std::vector<std::string> links = {"base", "arm", "gripper::palm", "gripper::finger"};
  for (size_t i = 0; i < links.size(); ++i) EXPECT_EQ(d.links[i].name, links[i]);
  ASSERT_EQ(d.joints.size(), 3u);
  EXPECT_EQ(d.joints[0].name, "shoulder");
  EXPECT_EQ(d.joints[1].name, "wrist");
  EXPECT_EQ(d.joints[1].child, "gripper::palm");
  EXPECT_EQ(d.joints[2].name, "gripper::slide");
  EXPECT_EQ(d.joints[2].parent, "gripper::palm");
  EXPECT_EQ(d.joints[2].child, "gripper::finger");
}

// Verifies the frames. The shoulder's frame (the arm's description frame)
// is at z = 0.5 - 0.1 = 0.4 in the model, turned 90 degrees about z; the
// base's at z = 0.1. So the shoulder's origin is z = 0.3 turned +90; the
// arm's inertial (z = 0.5 + 0.2 in the model) is at z = 0.3 in the joint
// frame, turned -90, and so is its capsule; the visual at z = 0.1. The
// gripper model sits at z = 1 turned +90: the wrist (at the palm) is 0.6
// above the shoulder frame with no turn left, the finger 0.1 along the
// palm's x.
TEST(SdfReaderTest, PosesAreResolvedIntoJointFrames) {
  const ModelDescription d = ReadArm();
  ExpectPose(d.joints[0].origin, Vec3(0, 0, 0.3), Yaw(kPi / 2), "shoulder origin");
  const Link& arm = d.links[1];
  ASSERT_TRUE(arm.inertial.has_value());
  ExpectPose(arm.inertial->origin, Vec3(0, 0, 0.3), Yaw(-kPi / 2), "arm inertial");
  ExpectPose(arm.collisions.at(0).origin, Vec3(0, 0, 0.3), Yaw(-kPi / 2), "arm capsule");
  ExpectPose(arm.visuals.at(0).origin, Vec3(0, 0, 0.1), Yaw(-kPi / 2), "arm visual");
  ExpectPose(d.joints[1].origin, Vec3(0, 0, 0.6), Quat::Identity(), "wrist origin");
  ExpectPose(d.joints[2].origin, Vec3(0.1, 0, 0), Quat::Identity(), "slide origin");
  ExpectPose(d.links[0].inertial->origin, Vec3::Zero(), Quat::Identity(), "base inertial");
}

// Verifies the inertia with its product, the axis given in the model frame
// and resolved in the turned joint frame (model y is joint x), limits,
// dynamics, and the geometry of each kind.
TEST(SdfReaderTest, InertiaAxesLimitsAndGeometryAreRead) {
  const ModelDescription d = ReadArm();
  Mat3 tensor;
  tensor << 0.02, 0.001, 0, 0.001, 0.02, 0, 0, 0, 0.01;
  EXPECT_NEAR(d.links[1].inertial->mass, 2.0, kTol);
  EXPECT_LT((d.links[1].inertial->inertia - tensor).norm(), kTol);

  const ModelJoint& shoulder = d.joints[0];
  EXPECT_EQ(shoulder.type, JointType::kRevolute);
  EXPECT_LT((shoulder.axis - Vec3::UnitX()).norm(), kTol) << shoulder.axis.transpose();
  ASSERT_TRUE(shoulder.limits.has_value());
  EXPECT_EQ(shoulder.limits->lower, -1.0);
  EXPECT_EQ(shoulder.limits->upper, 1.0);
  EXPECT_EQ(shoulder.limits->effort, 10.0);
  EXPECT_EQ(shoulder.limits->velocity, 3.0);
  EXPECT_EQ(shoulder.damping, 0.2);
  EXPECT_EQ(shoulder.friction, 0.05);
  EXPECT_EQ(d.joints[1].type, JointType::kFixed);
  EXPECT_EQ(d.joints[2].type, JointType::kPrismatic);
  EXPECT_LT((d.joints[2].axis - Vec3::UnitX()).norm(), kTol);
  EXPECT_EQ(d.joints[2].limits->upper, 0.04);
  EXPECT_EQ(d.joints[2].limits->effort, 0.0) << "SDF's -1 (no limit) is 0 in the description";

  const Geometry& capsule = d.links[1].collisions[0].geometry;
  EXPECT_EQ(capsule.type, GeometryType::kCapsule);
  EXPECT_EQ(capsule.radius, 0.05);
  EXPECT_EQ(capsule.length, 0.3);
  const VisualElement& visual = d.links[1].visuals[0];
  EXPECT_EQ(visual.geometry.mesh_path, DataDir() + "/tetra.obj");
  EXPECT_EQ(visual.geometry.mesh_scale, Vec3(2, 2, 2));
  EXPECT_LT((visual.rgba - Eigen::Vector4d(0, 1, 0, 1)).norm(), 1e-7);  // ignition colours are floats
  EXPECT_LT((d.links[0].collisions[0].geometry.box_size - Vec3(0.2, 0.3, 0.1)).norm(), kTol);
  EXPECT_EQ(d.links[2].collisions[0].geometry.type, GeometryType::kSphere);
  const Link& finger = d.links[3];
  EXPECT_EQ(finger.collisions[0].geometry.type, GeometryType::kCylinder);
  EXPECT_EQ(finger.collisions[0].geometry.length, 0.05);
  EXPECT_EQ(finger.collisions[1].geometry.mesh_path, DataDir() + "/models/tetra_model/meshes/tetra.obj");
  EXPECT_EQ(finger.collisions[1].geometry.mesh_vertices.size(), 4u);
}

// Verifies an <include> of model://tetra_model (found on the search path,
// its model.config naming tetra.sdf): its link is scoped by the include's
// <name>, placed by its <pose>, and its mesh, named relative to the
// included file, is found next to that file.
TEST(SdfReaderTest, IncludedModelsAreFoundPlacedAndScoped) {
  ModelDescription d;
  const std::string path = DataDir() + "/with_include.sdf";
  const Status st = ReadSdf(ReadText(path), path, ModelPaths{{DataDir() + "/models"}}, ReadLimits{}, &d);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(d.links.size(), 2u);
  EXPECT_EQ(d.links[1].name, "top::body");
  ASSERT_EQ(d.joints.size(), 1u);
  ExpectPose(d.joints[0].origin, Vec3(0, 0, 0.5), Quat::Identity(), "mount origin");
  const Geometry& hull = d.links[1].collisions.at(0).geometry;
  EXPECT_EQ(hull.mesh_path, DataDir() + "/models/tetra_model/meshes/tetra.obj");
  EXPECT_EQ(hull.mesh_vertices.size(), 4u);
  // without the search path the include is not found, and the message says which
  ModelDescription none;
  const Status missing = ReadSdf(ReadText(path), path, ModelPaths{}, ReadLimits{}, &none);
  EXPECT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("tetra_model"), std::string::npos) << missing.message();
}

// Verifies SDF 1.7 frames: a link placed relative_to a <frame> attached to
// another link (0.2 above it, turned 90 degrees about z, then 0.1 higher),
// and an axis expressed in the model frame: the model's x is the turned
// child's -y.
TEST(SdfReaderTest, FramesAndRelativePosesAreResolved) {
  const std::string text = Model(
      "<frame name=\"mount\" attached_to=\"a\"><pose>0 0 0.2 0 0 1.5707963267948966</pose></frame>\n" +
      SimpleLink("a") + "<link name=\"b\"><pose relative_to=\"mount\">0 0 0.1 0 0 0</pose></link>\n" +
      Joint("j", "continuous", "a", "b", "<axis><xyz expressed_in=\"__model__\">1 0 0</xyz></axis>"));
  ModelDescription d;
  const Status st = ReadSdf(text, "test.sdf", ModelPaths{}, ReadLimits{}, &d);
  ASSERT_TRUE(st.ok()) << st.message();
  ExpectPose(d.joints[0].origin, Vec3(0, 0, 0.3), Yaw(kPi / 2), "j origin");
  EXPECT_LT((d.joints[0].axis - Vec3(0, -1, 0)).norm(), kTol) << d.joints[0].axis.transpose();
}

// Verifies that a model inside a <world> is read, that an unbounded
// revolute becomes continuous, and a link without <inertial> takes SDF's
// default of 1 kg.
TEST(SdfReaderTest, WorldModelUnboundedRevoluteAndDefaultInertial) {
  const std::string text = "<sdf version=\"1.9\"><world name=\"w\"><model name=\"m\">" + SimpleLink("a") +
                           "<link name=\"b\"/>" + Joint("j", "revolute", "a", "b") + "</model></world></sdf>";
  ModelDescription d;
  const Status st = ReadSdf(text, "test.sdf", ModelPaths{}, ReadLimits{}, &d);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(d.joints[0].type, JointType::kContinuous);
  ASSERT_TRUE(d.links[1].inertial.has_value());
  EXPECT_EQ(d.links[1].inertial->mass, 1.0);
}

// Verifies the refusals: ball, universal, revolute2 and screw joints, a
// joint to the world, a plane, several models in a world, malformed XML,
// a negative mass (libsdformat checks inertias itself), a missing mesh, two
// roots and a loop.
TEST(SdfReaderTest, UnsupportedAndBadModelsAreRefused) {
  const std::string two = SimpleLink("a") + SimpleLink("b");
  ExpectRefused(Model(two + Joint("j", "ball", "a", "b", "")), {"test.sdf", "joint 'j'", "'ball' is not supported"});
  ExpectRefused(Model(two + Joint("j", "universal", "a", "b",
                                  "<axis><xyz>0 0 1</xyz></axis><axis2><xyz>0 1 0</xyz></axis2>")),
                {"joint 'j'", "'universal' is not supported"});
  ExpectRefused(Model(two + Joint("j", "revolute2", "a", "b",
                                  "<axis><xyz>0 0 1</xyz></axis><axis2><xyz>0 1 0</xyz></axis2>")),
                {"'revolute2' is not supported"});
  ExpectRefused(Model(two + Joint("j", "screw", "a", "b")), {"'screw' is not supported"});
  ExpectRefused(Model(two + Joint("j", "revolute", "a", "b") + Joint("w", "fixed", "world", "a", "")),
                {"joint 'w'", "to the world", "fixed base"});
  ExpectRefused(Model(SimpleLink("a", "<collision name=\"c\"><geometry><plane><normal>0 0 1</normal></plane>"
                                      "</geometry></collision>")),
                {"link 'a'", "collision 'c'", "plane"});
  ExpectRefused("<sdf version=\"1.9\"><world name=\"w\"><model name=\"m1\">" + SimpleLink("a") +
                    "</model><model name=\"m2\">" + SimpleLink("a") + "</model></world></sdf>",
                {"2 models", "'m1', 'm2'"});
  ExpectRefused("<sdf version=\"1.9\"><model name=\"m\"><link name=\"a\"></model></sdf>", {"test.sdf", "libsdformat"});
  ExpectRefused(Model("<link name=\"a\"/>\n<link name=\"b\"><inertial><mass>-2</mass></inertial></link>\n" +
                      Joint("j", "fixed", "a", "b", "")),
                {"test.sdf", "link named b has invalid inertia"});  // libsdformat's own check
  ExpectRefused(Model(SimpleLink("a", "<collision name=\"c\"><geometry><mesh><uri>gone.stl</uri></mesh></geometry>"
                                      "</collision>")),
                {"link 'a'", "gone.stl"});
  ExpectRefused(Model(two), {"2 root links"});
  ExpectRefused(Model(SimpleLink("a") + SimpleLink("b") + SimpleLink("c") + Joint("ab", "fixed", "a", "b", "") +
                      Joint("bc", "fixed", "b", "c", "") + Joint("ac", "fixed", "a", "c", "")),
                {"joint 'ac'", "kinematic loop"});
}

// Verifies that every cut of the fixture file is either read or refused
// with the file named, never a crash (run under the sanitizers in CI).
TEST(SdfReaderTest, CutFilesAreReadOrRefused) {
  const std::string path = DataDir() + "/arm.sdf";
  const std::string text = ReadText(path);
  for (size_t cut = 0; cut < text.size(); cut += 157) {  // libsdformat takes ~70 ms a file
    ModelDescription d;
    const Status st = ReadSdf(text.substr(0, cut), path, ModelPaths{{DataDir() + "/models"}}, ReadLimits{}, &d);
    ASSERT_FALSE(st.ok()) << "a cut file has no closing </sdf>: " << cut;
    EXPECT_NE(st.message().find("arm.sdf"), std::string::npos) << st.message();
  }
}

}  // namespace
}  // namespace contactsim::model
