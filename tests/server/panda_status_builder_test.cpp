// Tests of BuildPandaStatus: each field of Drake's Panda status carries the
// reading its meaning asks for, the drives' inputs read as Drake's
// control-mode bits, and a bad reading is refused without touching the
// message.
#include "service/server/arm_driver/panda_status_builder.h"

#include <contactsim/wire_check.hpp>
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace contactsim {
namespace {

std::vector<double> PandaValues(int n, double base) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = base + 0.1 * i;
  return v;
}

ArmJointReadings PandaReadings(int n) {
  ArmJointReadings r;
  r.position = PandaValues(n, 1.0);
  r.velocity = PandaValues(n, -2.0);
  r.position_commanded = PandaValues(n, 3.0);
  r.torque_commanded = PandaValues(n, 40.0);
  return r;
}

// Verifies every field for arms of several sizes, with the optional arrays
// left out (zeros; measured torque = commanded) and given.
TEST(PandaStatusBuilderTest, FieldsCarryTheirReadings) {
  for (int n : {1, 2, 7}) {
    ArmJointReadings r = PandaReadings(n);
    drake::lcmt_panda_status m;
    ASSERT_TRUE(BuildPandaStatus(1.25, r, &m).ok());
    EXPECT_EQ(m.utime, 1250000);
    EXPECT_EQ(m.robot_utime, 1250000);
    EXPECT_EQ(m.num_joints, n);
    EXPECT_EQ(m.joint_position, r.position);
    EXPECT_EQ(m.joint_position_desired, r.position_commanded);
    EXPECT_EQ(m.joint_velocity, r.velocity);
    EXPECT_EQ(m.joint_velocity_desired, std::vector<double>(n, 0.0));
    EXPECT_EQ(m.joint_acceleration_desired, std::vector<double>(n, 0.0));
    EXPECT_EQ(m.joint_torque, r.torque_commanded);
    EXPECT_EQ(m.joint_torque_desired, r.torque_commanded);
    EXPECT_EQ(m.joint_torque_external, std::vector<double>(n, 0.0));
    EXPECT_EQ(m.control_command_success_rate, 1.0);
    EXPECT_EQ(m.robot_mode, +drake::lcmt_panda_status::kIdle);
    EXPECT_EQ(m.control_mode, 0);
    r.velocity_commanded = PandaValues(n, 0.5);
    r.torque_applied = PandaValues(n, 39.0);
    r.torque_external = PandaValues(n, -5.0);
    ASSERT_TRUE(BuildPandaStatus(1.25, r, &m).ok());
    EXPECT_EQ(m.joint_velocity_desired, r.velocity_commanded);
    EXPECT_EQ(m.joint_torque, r.torque_applied);
    EXPECT_EQ(m.joint_torque_external, r.torque_external);
    std::string bytes(m.getEncodedSize(), '\0');
    ASSERT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
    std::string why;
    EXPECT_TRUE(wire::Check<drake::lcmt_panda_status>(bytes.data(), static_cast<int>(bytes.size()), &why)) << why;
  }
}

// Verifies that every set of the drives' inputs reads as the same set of
// Drake's CONTROL_MODE_* bits, and the robot moves while any input acts.
TEST(PandaStatusBuilderTest, InputsReadAsControlModeBits) {
  using S = drake::lcmt_panda_status;
  for (int inputs = 0; inputs <= 7; ++inputs) {
    ArmJointReadings r = PandaReadings(7);
    r.inputs = inputs;
    drake::lcmt_panda_status m;
    ASSERT_TRUE(BuildPandaStatus(0.5, r, &m).ok());
    const int want = ((inputs & kArmPositionInput) ? S::CONTROL_MODE_POSITION : 0) |
                     ((inputs & kArmVelocityInput) ? S::CONTROL_MODE_VELOCITY : 0) |
                     ((inputs & kArmTorqueInput) ? S::CONTROL_MODE_TORQUE : 0);
    EXPECT_EQ(m.control_mode, want);
    EXPECT_EQ(m.robot_mode, inputs != 0 ? +S::kMove : +S::kIdle);
  }
}

// Verifies that a bad reading is refused, names the field, and leaves the
// message as it was (the checks are CheckArmReadings', shared with the iiwa).
TEST(PandaStatusBuilderTest, BadReadingsAreRefused) {
  ArmJointReadings r = PandaReadings(7);
  r.velocity_commanded = PandaValues(6, 0.0);
  drake::lcmt_panda_status m{};
  m.utime = 42;
  Status st = BuildPandaStatus(1.0, r, &m);
  EXPECT_NE(st.message().find("velocity_commanded has 6 entries, the arm 7 joints"), std::string::npos)
      << st.message();
  r = PandaReadings(7);
  r.velocity[1] = std::numeric_limits<double>::quiet_NaN();
  st = BuildPandaStatus(1.0, r, &m);
  EXPECT_NE(st.message().find("velocity[1] is not finite"), std::string::npos) << st.message();
  st = BuildPandaStatus(-1.0, PandaReadings(7), &m);
  EXPECT_NE(st.message().find("sim_time_s"), std::string::npos) << st.message();
  EXPECT_EQ(m.utime, 42);
  EXPECT_EQ(m.num_joints, 0);
}

}  // namespace
}  // namespace contactsim
