// Tests of DecodeIiwaCommand and DecodePandaCommand, the total decoders of
// the arm driver's channel: a valid message is read whole, every
// truncation, extension and single-byte corruption of it is refused or read
// without a throw, oversized or non-finite commands are refused naming the
// field, and a Panda command's arrays follow its control-mode bits.
#include "service/server/arm_driver/arm_command.h"

#include <gtest/gtest.h>

#include <drake/lcmt_iiwa_command.hpp>
#include <drake/lcmt_panda_command.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

drake::lcmt_iiwa_command Valid() {
  drake::lcmt_iiwa_command m;
  m.utime = 123456;
  m.num_joints = 7;
  m.joint_position = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7};
  m.num_torques = 7;
  m.joint_torque = {1, 2, 3, 4, 5, 6, 7};
  return m;
}

// Verifies that a valid command is read whole, and that positions only and
// torques only (empty arrays) are read as such.
TEST(ArmCommandTest, ValidCommandIsReadWhole) {
  drake::lcmt_iiwa_command m = Valid();
  auto bytes = testing::Encode(m);
  ArmCommand c;
  ASSERT_TRUE(DecodeIiwaCommand(bytes.data(), static_cast<int>(bytes.size()), &c).ok());
  EXPECT_EQ(c.utime, m.utime);
  EXPECT_EQ(c.position, m.joint_position);
  EXPECT_EQ(c.torque, m.joint_torque);
  m.num_torques = 0;
  m.joint_torque.clear();
  bytes = testing::Encode(m);
  ASSERT_TRUE(DecodeIiwaCommand(bytes.data(), static_cast<int>(bytes.size()), &c).ok());
  EXPECT_TRUE(c.torque.empty());
}

// Verifies that every truncation and an extra byte are refused as
// undecodable, and that random single-byte corruptions never throw and
// never leave a command with arrays that disagree with the wire's counts.
TEST(ArmCommandTest, DamagedBytesAreRefusedWithoutAThrow) {
  const auto good = testing::Encode(Valid());
  for (size_t n = 0; n < good.size(); ++n) {
    ArmCommand c;
    EXPECT_EQ(DecodeIiwaCommand(good.data(), static_cast<int>(n), &c).code(), StatusCode::kDecodeError) << n;
  }
  std::vector<uint8_t> longer = good;
  longer.push_back(0);
  ArmCommand c;
  EXPECT_EQ(DecodeIiwaCommand(longer.data(), static_cast<int>(longer.size()), &c).code(), StatusCode::kDecodeError);
  EXPECT_EQ(DecodeIiwaCommand(nullptr, 0, &c).code(), StatusCode::kDecodeError);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5000; ++trial) {
    std::vector<uint8_t> bytes = good;
    bytes[rng() % bytes.size()] = static_cast<uint8_t>(rng());
    ArmCommand out;
    const Status st = DecodeIiwaCommand(bytes.data(), static_cast<int>(bytes.size()), &out);
    if (st.ok()) {
      for (double v : out.position) EXPECT_TRUE(std::isfinite(v));
      for (double v : out.torque) EXPECT_TRUE(std::isfinite(v));
    }
  }
}

// Verifies the refusals that name their cause: a payload over the size
// limit, and a NaN or infinity in either array, by field and index.
TEST(ArmCommandTest, OversizedAndNonFiniteCommandsAreRefused) {
  drake::lcmt_iiwa_command m = Valid();
  m.num_joints = 1000;
  m.joint_position.assign(1000, 0.0);
  auto bytes = testing::Encode(m);
  ArmCommand c;
  Status st = DecodeIiwaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
  EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
  EXPECT_NE(st.message().find("exceeds the limit of 4096 bytes"), std::string::npos) << st.message();
  m = Valid();
  m.joint_torque[5] = -std::numeric_limits<double>::infinity();
  bytes = testing::Encode(m);
  st = DecodeIiwaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("joint_torque[5] is -inf, not a finite number"), std::string::npos) << st.message();
  EXPECT_EQ(c.utime, m.utime);  // read, so that the refusal can name it
}

drake::lcmt_panda_command ValidPanda(int mode) {
  drake::lcmt_panda_command m;
  m.utime = 654321;
  const std::vector<double> v = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7};
  if (mode & kPandaPositionMode) m.joint_position = v;
  if (mode & kPandaVelocityMode) m.joint_velocity = v;
  if (mode & kPandaTorqueMode) m.joint_torque = v;
  m.num_joint_position = static_cast<int32_t>(m.joint_position.size());
  m.num_joint_velocity = static_cast<int32_t>(m.joint_velocity.size());
  m.num_joint_torque = static_cast<int32_t>(m.joint_torque.size());
  m.control_mode_expected = static_cast<int8_t>(mode);
  return m;
}

// Verifies that a Panda command of every mode is read whole, the arrays its
// bits ask for filled and the others empty.
TEST(ArmCommandTest, PandaCommandOfEveryModeIsReadWhole) {
  for (int mode = 1; mode <= 7; ++mode) {
    const drake::lcmt_panda_command m = ValidPanda(mode);
    const auto bytes = testing::Encode(m);
    ArmCommand c;
    const Status st = DecodePandaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
    ASSERT_TRUE(st.ok()) << mode << ": " << st.message();
    EXPECT_EQ(c.utime, m.utime);
    EXPECT_EQ(c.position, m.joint_position);
    EXPECT_EQ(c.velocity, m.joint_velocity);
    EXPECT_EQ(c.torque, m.joint_torque);
  }
}

// Verifies that a Panda command whose mode is none of Drake's, or whose
// arrays disagree with its bits, is refused naming both, and that damaged
// bytes are refused or read without a throw, as the iiwa's are.
TEST(ArmCommandTest, PandaModeAndArraysMustAgree) {
  for (int mode : {0, 8, 9, 16, 64, -128, -1}) {
    drake::lcmt_panda_command m = ValidPanda(mode & 7);
    m.control_mode_expected = static_cast<int8_t>(mode);
    const auto bytes = testing::Encode(m);
    ArmCommand c;
    const Status st = DecodePandaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << mode;
    EXPECT_NE(st.message().find("control_mode_expected " + std::to_string(mode) + " is not a control mode"),
              std::string::npos)
        << st.message();
  }
  drake::lcmt_panda_command m = ValidPanda(kPandaVelocityMode);
  m.joint_position = {1.0};
  m.num_joint_position = 1;
  auto bytes = testing::Encode(m);
  ArmCommand c;
  Status st = DecodePandaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
  EXPECT_NE(st.message().find("control_mode_expected 2 excludes joint_position (mode bit 1), but it has 1 entries"),
            std::string::npos)
      << st.message();
  m = ValidPanda(kPandaVelocityMode);
  m.joint_velocity[4] = std::numeric_limits<double>::quiet_NaN();
  bytes = testing::Encode(m);
  st = DecodePandaCommand(bytes.data(), static_cast<int>(bytes.size()), &c);
  EXPECT_NE(st.message().find("joint_velocity[4] is nan"), std::string::npos) << st.message();
  const auto good = testing::Encode(ValidPanda(7));
  for (size_t n = 0; n < good.size(); ++n) {
    EXPECT_EQ(DecodePandaCommand(good.data(), static_cast<int>(n), &c).code(), StatusCode::kDecodeError) << n;
  }
  const auto iiwa = testing::Encode(Valid());  // another type's fingerprint
  EXPECT_EQ(DecodePandaCommand(iiwa.data(), static_cast<int>(iiwa.size()), &c).code(), StatusCode::kDecodeError);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> damaged = good;
    damaged[rng() % damaged.size()] = static_cast<uint8_t>(rng());
    ArmCommand out;
    if (DecodePandaCommand(damaged.data(), static_cast<int>(damaged.size()), &out).ok()) {
      for (const auto* v : {&out.position, &out.velocity, &out.torque}) {
        for (double x : *v) EXPECT_TRUE(std::isfinite(x));
      }
    }
  }
}

}  // namespace
}  // namespace contactsim
