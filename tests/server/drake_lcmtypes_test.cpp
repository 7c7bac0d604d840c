// Tests of the generated C++ classes of Drake's arm-driver messages
// (lcmtypes/drake/): each encodes and decodes back to equal values, passes
// the wire check whole and is refused truncated or with a negative count.
// With CONTACTSIM_DRAKE_SAMPLE_DIR set, the samples' bytes are written there
// as <type>.bin, and tests/python/test_drake_lcmtypes.py compares them with
// the Python classes' encoding of the same values and with Drake's
// fingerprints.
//
// Sample values, the same rule on both sides: the field at position k (from
// 0, in declaration order) holds k + 0.5 (double), 1000 (k + 1) (int64), k
// (int8), element j of a double array k + j / 8; array counts are 7, except
// lcmt_panda_command's num_joint_velocity, 0 (an empty array on purpose).
#include <contactsim/wire_check.hpp>
#include <drake/lcmt_iiwa_command.hpp>
#include <drake/lcmt_iiwa_status.hpp>
#include <drake/lcmt_panda_command.hpp>
#include <drake/lcmt_panda_status.hpp>
#include <drake/lcmt_schunk_wsg_command.hpp>
#include <drake/lcmt_schunk_wsg_status.hpp>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace contactsim {
namespace {

constexpr int kJoints = 7;

std::vector<double> Ramp(int k, int n) {
  std::vector<double> v(n);
  for (int j = 0; j < n; ++j) v[j] = k + j / 8.0;
  return v;
}

drake::lcmt_iiwa_command IiwaCommand() {
  drake::lcmt_iiwa_command m;
  m.utime = 1000;
  m.num_joints = kJoints;
  m.joint_position = Ramp(2, kJoints);
  m.num_torques = kJoints;
  m.joint_torque = Ramp(4, kJoints);
  return m;
}

drake::lcmt_iiwa_status IiwaStatus() {
  drake::lcmt_iiwa_status m;
  m.utime = 1000;
  m.num_joints = kJoints;
  m.joint_position_measured = Ramp(2, kJoints);
  m.joint_velocity_estimated = Ramp(3, kJoints);
  m.joint_position_commanded = Ramp(4, kJoints);
  m.joint_position_ipo = Ramp(5, kJoints);
  m.joint_torque_measured = Ramp(6, kJoints);
  m.joint_torque_commanded = Ramp(7, kJoints);
  m.joint_torque_external = Ramp(8, kJoints);
  return m;
}

drake::lcmt_panda_command PandaCommand() {
  drake::lcmt_panda_command m;
  m.utime = 1000;
  m.num_joint_position = kJoints;
  m.joint_position = Ramp(2, kJoints);
  m.num_joint_velocity = 0;
  m.num_joint_torque = kJoints;
  m.joint_torque = Ramp(6, kJoints);
  m.control_mode_expected = 7;
  return m;
}

drake::lcmt_panda_status PandaStatus() {
  drake::lcmt_panda_status m;
  m.utime = 1000;
  m.num_joints = kJoints;
  m.joint_position = Ramp(2, kJoints);
  m.joint_position_desired = Ramp(3, kJoints);
  m.joint_velocity = Ramp(4, kJoints);
  m.joint_velocity_desired = Ramp(5, kJoints);
  m.joint_acceleration_desired = Ramp(6, kJoints);
  m.joint_torque = Ramp(7, kJoints);
  m.joint_torque_desired = Ramp(8, kJoints);
  m.joint_torque_external = Ramp(9, kJoints);
  m.control_command_success_rate = 10.5;
  m.robot_mode = 11;
  m.robot_utime = 13000;
  m.control_mode = 13;
  return m;
}

drake::lcmt_schunk_wsg_command WsgCommand() {
  drake::lcmt_schunk_wsg_command m;
  m.utime = 1000;
  m.target_position_mm = 1.5;
  m.force = 2.5;
  return m;
}

drake::lcmt_schunk_wsg_status WsgStatus() {
  drake::lcmt_schunk_wsg_status m;
  m.utime = 1000;
  m.actual_position_mm = 1.5;
  m.actual_force = 2.5;
  m.actual_speed_mm_per_s = 3.5;
  return m;
}

template <typename Msg>
std::string Encode(const Msg& m) {
  std::string bytes(m.getEncodedSize(), '\0');
  EXPECT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return bytes;
}

// Round trip, wire check whole and broken, and the sample file when asked.
template <typename Msg>
void CheckSample(const Msg& sent) {
  const std::string bytes = Encode(sent);
  std::string why;
  EXPECT_TRUE(wire::Check<Msg>(bytes.data(), static_cast<int>(bytes.size()), &why)) << why;
  for (size_t cut : {bytes.size() - 1, size_t{8}, size_t{3}}) {
    why.clear();
    EXPECT_FALSE(wire::Check<Msg>(bytes.data(), static_cast<int>(cut), &why))
        << Msg::getTypeName() << " cut at " << cut;
    EXPECT_FALSE(why.empty());
  }
  Msg received;
  ASSERT_EQ(received.decode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  EXPECT_EQ(Encode(received), bytes) << Msg::getTypeName();
  if (const char* dir = std::getenv("CONTACTSIM_DRAKE_SAMPLE_DIR")) {
    std::ofstream(std::string(dir) + "/" + Msg::getTypeName() + ".bin", std::ios::binary) << bytes;
  }
}

// Verifies each message's encoding survives a decode and passes the wire
// check only whole.
TEST(DrakeLcmtypesTest, EveryMessageRoundTripsAndIsCheckedOnTheWire) {
  CheckSample(IiwaCommand());
  CheckSample(IiwaStatus());
  CheckSample(PandaCommand());
  CheckSample(PandaStatus());
  CheckSample(WsgCommand());
  CheckSample(WsgStatus());
}

// Verifies that a negative or oversized joint count is refused before the
// generated decoder would size a vector with it (50 doubles need 400 bytes,
// 392 remain). num_joints of
// lcmt_iiwa_status sits after the fingerprint and utime, at byte 16.
TEST(DrakeLcmtypesTest, WireCheckRefusesBadJointCounts) {
  std::string bytes = Encode(IiwaStatus());
  for (uint32_t count : {0xffffffffu, 0x7fffffffu, 50u}) {
    std::string bad = bytes;
    for (int i = 0; i < 4; ++i) bad[16 + i] = static_cast<char>(count >> (24 - 8 * i));
    std::string why;
    EXPECT_FALSE(wire::Check<drake::lcmt_iiwa_status>(bad.data(), static_cast<int>(bad.size()), &why)) << count;
    EXPECT_NE(why.find("joint_position_measured"), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace contactsim
