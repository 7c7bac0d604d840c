// Tests of URDF <mimic>: the reader takes the master, multiplier and
// offset; the builder makes the world joint a mimic of its master; and
// every bad mimic (unknown joint, itself, a cycle, joints of different
// kinds, a non-finite multiplier) is refused with the joint named and
// nothing loaded.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "service/model/model_adder.h"
#include "service/model/model_builder.h"
#include "service/model/model_check.h"
#include "service/model/urdf_reader.h"

namespace contactsim::model {
namespace {

std::string Link(const std::string& name) {
  return "<link name=\"" + name +
         "\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>"
         "</inertial><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>";
}

// A joint from the base to `child` of `type`, with the extra `inner` XML.
std::string Joint(const std::string& name, const std::string& type, const std::string& child,
                  const std::string& inner = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"base\"/><child link=\"" + child +
         "\"/><axis xyz=\"1 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>" + inner +
         "</joint>";
}

std::string Mimic(const std::string& joint, const std::string& extra = "") {
  return "<mimic joint=\"" + joint + "\"" + extra + "/>";
}

// Three fingers on the base: joints a, b, c of the given types with the
// given inner XML each.
std::string Hand(const std::vector<std::string>& types, const std::vector<std::string>& inner) {
  std::string text = "<robot name=\"hand\">" + Link("base");
  const char* names[] = {"a", "b", "c"};
  for (size_t i = 0; i < types.size(); ++i) text += Link(std::string("f") + names[i]);
  for (size_t i = 0; i < types.size(); ++i) text += Joint(names[i], types[i], std::string("f") + names[i], inner[i]);
  return text + "</robot>";
}

Status Read(const std::string& text, ModelDescription* d) {
  return ReadUrdf(text, "hand.urdf", ModelPaths{}, ReadLimits{}, d);
}

void ExpectRefused(const std::string& text, const std::vector<std::string>& needles) {
  ModelDescription d;
  d.name = "untouched";
  const Status st = Read(text, &d);
  ASSERT_FALSE(st.ok()) << text;
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  for (const std::string& n : needles) EXPECT_NE(st.message().find(n), std::string::npos) << st.message();
  EXPECT_EQ(d.name, "untouched");
}

// Verifies that the reader keeps a mimic's master, multiplier and offset,
// with URDF's defaults (1, 0) when they are left out.
TEST(MimicCheckTest, MimicIsRead) {
  ModelDescription d;
  const Status st = Read(Hand({"prismatic", "prismatic", "prismatic"},
                              {"", Mimic("a", " multiplier=\"-0.5\" offset=\"0.01\""), Mimic("a")}),
                         &d);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(d.joints.size(), 3u);
  EXPECT_FALSE(d.joints[0].mimic.has_value());
  ASSERT_TRUE(d.joints[1].mimic.has_value());
  EXPECT_EQ(d.joints[1].mimic->joint, "a");
  EXPECT_EQ(d.joints[1].mimic->multiplier, -0.5);
  EXPECT_EQ(d.joints[1].mimic->offset, 0.01);
  ASSERT_TRUE(d.joints[2].mimic.has_value());
  EXPECT_EQ(d.joints[2].mimic->multiplier, 1.0);
  EXPECT_EQ(d.joints[2].mimic->offset, 0.0);
}

// Verifies that a revolute joint may mimic a continuous one (both are
// hinges), and that a chain of mimics (c -> b -> a) is taken.
TEST(MimicCheckTest, HingesOfEitherTypeAndChainsAreTaken) {
  ModelDescription d;
  const Status st = Read(Hand({"continuous", "revolute", "revolute"}, {"", Mimic("a"), Mimic("b")}), &d);
  EXPECT_TRUE(st.ok()) << st.message();
}

// Verifies each refusal, with the mimic joint and the reason named.
TEST(MimicCheckTest, BadMimicsAreRefused) {
  ExpectRefused(Hand({"revolute", "revolute"}, {"", Mimic("nobody")}),
                {"joint 'b'", "mimic names joint 'nobody'", "does not have"});
  ExpectRefused(Hand({"revolute", "revolute"}, {"", Mimic("b")}), {"joint 'b'", "itself"});
  ExpectRefused(Hand({"revolute", "revolute", "revolute"}, {Mimic("c"), Mimic("a"), Mimic("b")}),
                {"cycle", "->"});
  ExpectRefused(Hand({"revolute", "prismatic"}, {"", Mimic("a")}),
                {"joint 'b'", "prismatic joint cannot mimic the revolute joint 'a'"});
  ExpectRefused(Hand({"fixed", "revolute"}, {"", Mimic("a")}), {"cannot mimic the fixed joint 'a'"});
}

// Verifies that a description whose multiplier or offset is not finite
// (urdfdom's number parser takes no "nan", so the description comes from
// code) is refused by the builder's check with the joint named.
TEST(MimicCheckTest, NonFiniteMultiplierIsRefused) {
  ModelDescription d;
  ASSERT_TRUE(Read(Hand({"prismatic", "prismatic"}, {"", Mimic("a")}), &d).ok());
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    ModelDescription copy = d;
    copy.joints[1].mimic->multiplier = bad;
    ModelBuild build;
    const Status st = BuildModel(copy, ModelOptions{}, &build);
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.message().find("mimic multiplier"), std::string::npos) << st.message();
    EXPECT_NE(st.message().find("must be finite"), std::string::npos) << st.message();
    EXPECT_TRUE(build.joints.empty());
  }
}

// Verifies that the loaded world joint is a mimic of its master, with the
// file's multiplier and offset, and that removing the model removes both.
TEST(MimicCheckTest, LoadedJointMimicsItsMaster) {
  ModelDescription d;
  ASSERT_TRUE(Read(Hand({"prismatic", "prismatic"}, {"", Mimic("a", " multiplier=\"-1\" offset=\"0.02\"")}), &d).ok());
  ModelBuild build;
  const Status built = BuildModel(d, ModelOptions{}, &build);
  ASSERT_TRUE(built.ok()) << built.message();
  World world;
  PreparedModel prepared;
  ASSERT_TRUE(PrepareModel(std::move(build), world, Material{}, &prepared).ok());
  ModelRecord record;
  ASSERT_TRUE(CommitModel(std::move(prepared), &world, &record).ok());
  const contactsim::Joint* b = world.FindJoint(record.joints[1].joint);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->mimic.master, record.joints[0].joint);
  EXPECT_EQ(b->mimic.multiplier, -1.0);
  EXPECT_EQ(b->mimic.offset, 0.02);
  EXPECT_TRUE(world.HasJointMimics());
  ModelRecord removed;
  ASSERT_TRUE(RemoveModel(record.id, &world, &removed).ok());
  EXPECT_FALSE(world.HasJointMimics());
}

}  // namespace
}  // namespace contactsim::model
