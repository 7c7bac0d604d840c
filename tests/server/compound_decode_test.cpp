// Tests of the ADD fields of compound bodies and explicit mass properties
// (body_cmd_t COMPOUND, part_*, center_of_mass, inertia): a good message
// builds the body, every inconsistent count or bad part is refused with a
// message naming it, and nothing is built.
#include <contactsim/body_cmd_t.hpp>
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "service/server/command_channels.h"
#include "tests/server/command_messages.h"

namespace contactsim {
namespace {

using testing::EncodeMessage;

body_cmd_t SampleCompound() {
  for (const testing::SampleMessage& m : testing::SampleCommandMessages()) {
    if (m.label != "BODY_CMD ADD compound") continue;
    body_cmd_t msg;
    msg.decode(m.bytes.data(), 0, static_cast<int>(m.bytes.size()));
    return msg;
  }
  ADD_FAILURE() << "no compound sample";
  return body_cmd_t();
}

Status Decode(const body_cmd_t& m, Command* cmd, const DecodeContext& context = DecodeContext{}) {
  const std::string bytes = EncodeMessage(m);
  return ChannelOfSuffix("BODY_CMD")->decode(bytes.data(), static_cast<int>(bytes.size()), context, cmd);
}

// Verifies the sample compound decodes into the body it describes: two
// children about the explicit centre of mass, the six inertia values as a
// symmetric tensor, the frame's origin kept.
TEST(CompoundDecodeTest, ACompoundWithAnInertialBuildsItsBody) {
  Command cmd;
  const Status st = Decode(SampleCompound(), &cmd);
  ASSERT_TRUE(st.ok()) << st.message();
  const RigidBody& b = cmd.new_body;
  ASSERT_EQ(b.shape.type, ShapeType::kCompound);
  ASSERT_EQ(b.shape.compound->children.size(), 2u);
  EXPECT_EQ(b.shape.compound->children[1].shape.type, ShapeType::kConvex);
  EXPECT_TRUE(b.x.isApprox(Vec3(0.05, 0, 1.0), 1e-15));
  EXPECT_TRUE(b.frame_origin.isApprox(Vec3(-0.05, 0, 0), 1e-15));
  Mat3 I;
  I << 0.02, 0.001, -0.002, 0.001, 0.03, 0.0005, -0.002, 0.0005, 0.025;
  EXPECT_TRUE(b.inertia_body.isApprox(I, 1e-15));
  EXPECT_TRUE(b.explicit_inertia);
  EXPECT_EQ(b.mass, 2.0);
}

// Verifies each bad compound field is INVALID_ARGUMENT naming it (or
// RESOURCE_EXHAUSTED for the limits), before anything is built.
TEST(CompoundDecodeTest, BadPartsAndCountsAreRefusedByName) {
  struct Case {
    const char* says;
    std::function<void(body_cmd_t&)> damage;
    StatusCode code = StatusCode::kInvalidArgument;
  };
  const std::vector<Case> cases = {
      {"a compound takes 1 to 64 parts, got 0",
       [](body_cmd_t& m) {
         m.num_parts = 0;
         m.part_shape.clear();
         m.part_radius.clear();
         m.part_half_extents.clear();
         m.part_half_length.clear();
         m.part_num_points.clear();
         m.part_position.clear();
         m.part_orientation.clear();
         m.num_part_points = 0;
         m.part_points.clear();
       }},
      {"part_shape[0] must be SPHERE=1, BOX=2, CAPSULE=4 or CONVEX=5, got 9", [](body_cmd_t& m) { m.part_shape[0] = 9; }},
      {"parts[0].type must be sphere, box, capsule or convex, got plane",
       [](body_cmd_t& m) { m.part_shape[0] = body_cmd_t::PLANE; }},
      {"parts[0].type must be sphere, box, capsule or convex, got compound",
       [](body_cmd_t& m) { m.part_shape[0] = body_cmd_t::COMPOUND; }},
      {"parts[1].position must be finite", [](body_cmd_t& m) { m.part_position[1][2] = std::nan(""); }},
      {"parts[0].orientation must be a unit quaternion", [](body_cmd_t& m) { m.part_orientation[0] = {0, 0, 0, 0}; }},
      {"num_part_points must be the sum of part_num_points (4), got 3",
       [](body_cmd_t& m) {
         m.num_part_points = 3;
         m.part_points.pop_back();
       }},
      {"part_num_points[1] must be >= 0, got -1", [](body_cmd_t& m) { m.part_num_points[1] = -1; }},
      {"num_parts is for shape COMPOUND=6", [](body_cmd_t& m) { m.shape = body_cmd_t::BOX; }},
      {"positive definite", [](body_cmd_t& m) { m.inertia[0] = -0.02; }},
      {"triangle inequality",
       [](body_cmd_t& m) {
         const double diagonal[6] = {0.01, 0.01, 0.05, 0, 0, 0};
         std::copy(diagonal, diagonal + 6, m.inertia);
       }},
      {"an explicit inertia needs an explicit mass", [](body_cmd_t& m) { m.mass = 0.0; }},
      {"center_of_mass must be finite", [](body_cmd_t& m) { m.center_of_mass[1] = std::nan(""); }},
      {"num_parts 65 exceeds 64",
       [](body_cmd_t& m) {
         for (int k = 0; k < 63; ++k) {
           m.part_shape.push_back(int8_t{body_cmd_t::SPHERE});
           m.part_radius.push_back(0.1);
           m.part_half_extents.push_back({0, 0, 0});
           m.part_half_length.push_back(0);
           m.part_num_points.push_back(0);
           m.part_position.push_back({0, 0, 0});
           m.part_orientation.push_back({1, 0, 0, 0});
         }
         m.num_parts = 65;
       },
       StatusCode::kResourceExhausted},
  };
  for (const Case& c : cases) {
    body_cmd_t m = SampleCompound();
    c.damage(m);
    Command cmd;
    const Status st = Decode(m, &cmd);
    EXPECT_EQ(st.code(), c.code) << c.says << ": " << st.message();
    EXPECT_NE(st.message().find(c.says), std::string::npos) << st.message();
    EXPECT_EQ(cmd.new_body.shape.compound, nullptr) << c.says;
  }
  // the parts' points share the bound of one hull's
  DecodeContext context;
  context.limits.max_convex_points = 3;
  Command cmd;
  const Status st = Decode(SampleCompound(), &cmd, context);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("num_part_points 4 exceeds max_convex_points = 3"), std::string::npos) << st.message();
}

}  // namespace
}  // namespace contactsim
