// Tests of BuildIiwaStatus: each field of Drake's iiwa status carries the
// reading its meaning asks for, for arms of 1 to 7 joints, and bad readings
// are refused without touching the message.
#include "service/server/arm_driver/iiwa_status_builder.h"

#include <contactsim/wire_check.hpp>
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace contactsim {
namespace {

std::vector<double> Values(int n, double base) {
  std::vector<double> v(n);
  for (int i = 0; i < n; ++i) v[i] = base + 0.1 * i;
  return v;
}

ArmJointReadings Readings(int n) {
  ArmJointReadings r;
  r.position = Values(n, 1.0);
  r.velocity = Values(n, -2.0);
  r.position_commanded = Values(n, 3.0);
  r.torque_commanded = Values(n, 40.0);
  return r;
}

// Verifies every field for arms of several sizes, with the optional torques
// left out (measured = commanded, external = 0) and given.
TEST(IiwaStatusBuilderTest, FieldsCarryTheirReadings) {
  for (int n : {1, 2, 7}) {
    ArmJointReadings r = Readings(n);
    drake::lcmt_iiwa_status m;
    ASSERT_TRUE(BuildIiwaStatus(1.25, r, &m).ok());
    EXPECT_EQ(m.utime, 1250000);
    EXPECT_EQ(m.num_joints, n);
    EXPECT_EQ(m.joint_position_measured, r.position);
    EXPECT_EQ(m.joint_velocity_estimated, r.velocity);
    EXPECT_EQ(m.joint_position_commanded, r.position_commanded);
    EXPECT_EQ(m.joint_position_ipo, r.position_commanded);
    EXPECT_EQ(m.joint_torque_commanded, r.torque_commanded);
    EXPECT_EQ(m.joint_torque_measured, r.torque_commanded);
    EXPECT_EQ(m.joint_torque_external, std::vector<double>(n, 0.0));
    r.torque_applied = Values(n, 39.0);
    r.torque_external = Values(n, -5.0);
    ASSERT_TRUE(BuildIiwaStatus(1.25, r, &m).ok());
    EXPECT_EQ(m.joint_torque_measured, r.torque_applied);
    EXPECT_EQ(m.joint_torque_external, r.torque_external);
    // the message is complete: it encodes and passes the wire check
    std::string bytes(m.getEncodedSize(), '\0');
    ASSERT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
    std::string why;
    EXPECT_TRUE(wire::Check<drake::lcmt_iiwa_status>(bytes.data(), static_cast<int>(bytes.size()), &why)) << why;
  }
}

// Verifies that utime is the simulated time in whole microseconds, rounded:
// every sum of 5 ms steps reads its multiple of 5000 us, though the 10th sum
// is 0.049999999999999996 s, which truncation would read as 49999 us.
TEST(IiwaStatusBuilderTest, UtimeIsSimulatedMicrosecondsRounded) {
  double t = 0;
  drake::lcmt_iiwa_status m;
  for (int i = 1; i <= 1000; ++i) {
    t += 0.005;
    ASSERT_TRUE(BuildIiwaStatus(t, Readings(7), &m).ok());
    ASSERT_EQ(m.utime, 5000LL * i) << i;
  }
  ASSERT_TRUE(BuildIiwaStatus(0.0, Readings(7), &m).ok());
  EXPECT_EQ(m.utime, 0);
  ASSERT_TRUE(BuildIiwaStatus(3600.0000004, Readings(7), &m).ok());
  EXPECT_EQ(m.utime, 3600000000LL);
}

// Verifies that each bad reading is refused, names what is wrong and leaves
// the message as it was.
TEST(IiwaStatusBuilderTest, BadReadingsAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    double t;
    ArmJointReadings r;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({1.0, Readings(0), "no joints"});
  cases.push_back({-0.001, Readings(7), "sim_time_s"});
  cases.push_back({nan, Readings(7), "sim_time_s"});
  cases.push_back({1.0, Readings(7), "velocity has 6 entries, the arm 7 joints"});
  cases.back().r.velocity.pop_back();
  cases.push_back({1.0, Readings(7), "position_commanded has 0 entries"});
  cases.back().r.position_commanded.clear();
  cases.push_back({1.0, Readings(7), "torque_applied has 8 entries"});
  cases.back().r.torque_applied = Values(8, 0.0);
  cases.push_back({1.0, Readings(7), "torque_external has 1 entries"});
  cases.back().r.torque_external = {0.0};
  cases.push_back({1.0, Readings(7), "position[3] is not finite"});
  cases.back().r.position[3] = nan;
  cases.push_back({1.0, Readings(7), "torque_commanded[6] is not finite"});
  cases.back().r.torque_commanded[6] = std::numeric_limits<double>::infinity();
  for (const Case& k : cases) {
    drake::lcmt_iiwa_status m{};  // value-initialized: num_joints 0
    m.utime = 42;
    const Status st = BuildIiwaStatus(k.t, k.r, &m);
    ASSERT_FALSE(st.ok()) << k.says;
    EXPECT_NE(st.message().find(k.says), std::string::npos) << st.message();
    EXPECT_EQ(m.utime, 42);
    EXPECT_EQ(m.num_joints, 0);
  }
}

}  // namespace
}  // namespace contactsim
