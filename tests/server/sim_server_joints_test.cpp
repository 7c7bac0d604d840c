// Tests of the joint commands (joint_cmd_t on <P>_JOINT_CMD) through the
// server logic and a recording transport.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/server/sim_server_fixture.h"

namespace contactsim {
namespace {

class SimServerJointsTest : public testing::SimServerTest {};

// Verifies that ADD answers with the new joint id, REMOVE removes it, and
// removing a body says that it took its joints along.
TEST_F(SimServerJointsTest, AddAndRemoveJointsReplyWithIds) {
  const int64_t a = Send(Sphere(0.1, Vec3(0, 0, 1))).ids[0];
  const int64_t b = Send(Sphere(0.1, Vec3(0, 0, 2))).ids[0];
  reply_t r = Send(Joint(joint_cmd_t::DISTANCE, a, 0, Vec3(0, 0, 3)));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  ASSERT_EQ(r.num_ids, 1);
  EXPECT_EQ(r.ids[0], 1);
  EXPECT_EQ(r.message, "added distance joint 1");
  EXPECT_DOUBLE_EQ(server_.world().FindJoint(1)->length, 2.0);
  joint_cmd_t hinge = Joint(joint_cmd_t::HINGE, b, a, Vec3(0, 0, 1.5));
  hinge.has_axis = true;
  hinge.axis[1] = 2.0;
  hinge.has_limits = true;
  hinge.lower = -0.5;
  hinge.upper = 0.5;
  r = Send(hinge);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.ids[0], 2);
  EXPECT_TRUE(server_.world().FindJoint(2)->limited);

  joint_cmd_t remove{};
  remove.client_id = "test";
  remove.op = joint_cmd_t::REMOVE;
  remove.joint_id = 1;
  EXPECT_EQ(Send(remove).code, reply_t::OK);
  EXPECT_EQ(Send(remove).code, reply_t::NOT_FOUND);
  body_cmd_t remove_body{};
  remove_body.client_id = "test";
  remove_body.op = body_cmd_t::REMOVE;
  remove_body.body_id = a;
  r = Send(remove_body);
  EXPECT_EQ(r.message, "removed body 1 and its 1 joint(s)");
  EXPECT_TRUE(server_.world().joints().empty());
}

// Verifies that bad joint commands get an error naming the field and value
// and leave the world bit-identical (and the next joint id unused).
TEST_F(SimServerJointsTest, BadJointCommandsAreRejectedAndLeaveTheWorld) {
  const int64_t a = Send(Sphere(0.1, Vec3(0, 0, 1))).ids[0];
  const uint64_t before = HashWorldState(server_.world());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    joint_cmd_t cmd;
    int32_t code;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({Joint(joint_cmd_t::BALL, 42, 0, Vec3::Zero()), reply_t::NOT_FOUND, "body_a: unknown body id 42"});
  cases.push_back({Joint(joint_cmd_t::BALL, a, 43, Vec3::Zero()), reply_t::NOT_FOUND, "body_b: unknown body id 43"});
  cases.push_back({Joint(joint_cmd_t::BALL, a, a, Vec3::Zero()), reply_t::INVALID_ARGUMENT, "jointed to itself"});
  cases.push_back({Joint(joint_cmd_t::BALL, a, 0, Vec3(nan, 0, 0)), reply_t::INVALID_ARGUMENT, "anchor"});
  cases.push_back({Joint(9, a, 0, Vec3::Zero()), reply_t::INVALID_ARGUMENT, "kind must be one of"});
  joint_cmd_t zero_length = Joint(joint_cmd_t::DISTANCE, a, 0, Vec3(0, 0, 2));
  zero_length.has_length = true;
  cases.push_back({zero_length, reply_t::INVALID_ARGUMENT, "length must be a finite number > 0, got 0"});
  joint_cmd_t no_axis = Joint(joint_cmd_t::HINGE, a, 0, Vec3::Zero());
  no_axis.has_axis = true;
  cases.push_back({no_axis, reply_t::INVALID_ARGUMENT, "axis must be a finite nonzero vector, got (0, 0, 0)"});
  joint_cmd_t swapped = Joint(joint_cmd_t::HINGE, a, 0, Vec3::Zero());
  swapped.has_axis = true;
  swapped.axis[0] = 1.0;
  swapped.has_limits = true;
  swapped.lower = 1.0;
  cases.push_back({swapped, reply_t::INVALID_ARGUMENT, "lower <= upper"});
  joint_cmd_t remove{};
  remove.op = joint_cmd_t::REMOVE;
  remove.joint_id = 7;
  cases.push_back({remove, reply_t::NOT_FOUND, "unknown joint id 7"});
  for (const Case& c : cases) {
    const reply_t r = Send(c.cmd);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_NE(r.message.find(c.says), std::string::npos) << r.message;
    EXPECT_EQ(HashWorldState(server_.world()), before) << c.says;
  }
  EXPECT_EQ(Send(Joint(joint_cmd_t::BALL, a, 0, Vec3(0, 0, 2))).ids[0], 1);
}

// Verifies that a PRISMATIC joint with limits (m), damping and friction is
// added with them, and that its garbage (no axis, inverted or NaN limits,
// negative damping or friction, friction on a ball joint) is refused with a
// message naming the field and the value, the world left as it was.
TEST_F(SimServerJointsTest, PrismaticJointsCarryLimitsDampingAndFriction) {
  const int64_t a = Send(Sphere(0.1, Vec3(0, 0, 1))).ids[0];
  joint_cmd_t slider = Joint(joint_cmd_t::PRISMATIC, a, 0, Vec3(0, 0, 1));
  const uint64_t before = HashWorldState(server_.world());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    joint_cmd_t cmd;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({slider, "axis is required for a prismatic joint"});
  slider.has_axis = true;
  slider.axis[2] = 1.0;
  slider.has_limits = true;
  slider.lower = 0.2;
  slider.upper = -0.2;
  cases.push_back({slider, "limits must have lower <= upper, got lower 0.2 > upper -0.2"});
  slider.upper = nan;
  cases.push_back({slider, "limits.upper must be a finite number, got nan"});
  slider.lower = -0.5;
  slider.upper = 2.5;
  slider.has_damping = true;
  slider.damping = -1.0;
  cases.push_back({slider, "damping must be a finite number >= 0, got -1"});
  slider.damping = 3.0;
  slider.has_friction = true;
  slider.friction = nan;
  cases.push_back({slider, "friction must be a finite number >= 0, got nan"});
  joint_cmd_t ball = Joint(joint_cmd_t::BALL, a, 0, Vec3(0, 0, 2));
  ball.has_friction = true;
  ball.friction = 1.0;
  cases.push_back({ball, "friction applies to hinge and prismatic joints only, not ball"});
  for (const Case& c : cases) {
    const reply_t r = Send(c.cmd);
    EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT) << r.message;
    EXPECT_NE(r.message.find(c.says), std::string::npos) << r.message;
    EXPECT_EQ(HashWorldState(server_.world()), before) << c.says;
  }
  slider.friction = 0.5;
  const reply_t r = Send(slider);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.message, "added prismatic joint 1");
  const contactsim::Joint* j = server_.world().FindJoint(r.ids[0]);
  ASSERT_NE(j, nullptr);
  EXPECT_EQ(j->kind, JointKind::kPrismatic);
  EXPECT_TRUE(j->limited);
  EXPECT_EQ(j->lower, -0.5);
  EXPECT_EQ(j->upper, 2.5);
  EXPECT_EQ(j->damping, 3.0);
  EXPECT_EQ(j->friction, 0.5);
}

// Verifies that an undecodable joint payload gets a DECODE_ERROR reply.
TEST_F(SimServerJointsTest, UndecodableJointPayloadGetsDecodeError) {
  const uint8_t garbage[] = {1, 2, 3};
  server_.OnMessage(server_.Channel("JOINT_CMD"), garbage, sizeof garbage);
  const reply_t r = transport_.All<reply_t>("T_REPLY").back();
  EXPECT_EQ(r.code, reply_t::DECODE_ERROR);
  EXPECT_NE(r.message.find("T_JOINT_CMD"), std::string::npos);
}

}  // namespace
}  // namespace contactsim
