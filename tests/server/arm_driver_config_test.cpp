// Tests of the server config's arm_driver block: Drake's defaults fill
// absent fields, each bad field is refused with its name and line, the
// gains and the model paths' wildcards, and which protocol starts.
#include "service/server/arm_driver/arm_driver_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "service/server/server_config.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

proto::ArmDriver Block(const std::string& protocol, const std::string& model) {
  proto::ArmDriver b;
  b.set_protocol(protocol);
  b.set_model(model);
  return b;
}

// Verifies that each protocol takes the channel names of Drake's driver and
// its status rate when the block leaves them out: 200 Hz for the iiwa
// (Drake's kIiwaLcmStatusPeriod), 1 kHz for the Panda (libfranka's cycle).
TEST(ArmDriverConfigTest, AbsentFieldsTakeDrakesDefaults) {
  for (const char* protocol : {"iiwa", "panda"}) {
    ArmDriverConfig c;
    std::string field;
    ASSERT_TRUE(ReadArmDriverConfig(Block(protocol, "arm"), "CONTACTSIM", &c, &field).ok()) << protocol;
    EXPECT_EQ(c.model, "arm");
    EXPECT_DOUBLE_EQ(c.status_rate_hz, std::string(protocol) == "iiwa" ? 200.0 : 1000.0);
    const std::string upper = std::string(protocol) == "iiwa" ? "IIWA" : "PANDA";
    EXPECT_EQ(c.command_channel, upper + "_COMMAND");
    EXPECT_EQ(c.status_channel, upper + "_STATUS");
  }
}

// Verifies that every bad value is refused and names its field.
TEST(ArmDriverConfigTest, BadValuesNameTheirField) {
  struct Case {
    proto::ArmDriver block;
    const char* field;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({Block("kuka", "arm"), "protocol", "\"iiwa\" or \"panda\""});
  cases.push_back({Block("", "arm"), "protocol", "got \"\""});
  cases.push_back({Block("iiwa", ""), "model", "model must name"});
  for (const char* bad : {"", "HAS SPACE", "TAB\t"}) {
    cases.push_back({Block("iiwa", "arm"), "command_channel", "printable"});
    cases.back().block.set_command_channel(bad);
  }
  cases.push_back({Block("iiwa", "arm"), "status_channel", "among the server's own channels (CONTACTSIM_*)"});
  cases.back().block.set_status_channel("CONTACTSIM_STATE");
  cases.push_back({Block("panda", "arm"), "status_channel", "channels of their own"});
  cases.back().block.set_status_channel("PANDA_COMMAND");
  for (double rate : {0.0, -1.0, 1000.5, std::numeric_limits<double>::quiet_NaN(),
                      std::numeric_limits<double>::infinity()}) {
    cases.push_back({Block("iiwa", "arm"), "status_rate_hz", "(0, 1000] Hz"});
    cases.back().block.set_status_rate_hz(rate);
  }
  for (int n : {2, 8}) {
    cases.push_back({Block("iiwa", "arm"), "kp", "give none, one for every joint, or one per joint (7)"});
    for (int i = 0; i < n; ++i) cases.back().block.add_kp(100);
  }
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    cases.push_back({Block("iiwa", "arm"), "kd", "kd[0] must be finite and >= 0"});
    cases.back().block.add_kd(bad);
  }
  cases.push_back({Block("iiwa", "arm"), "load", "load.path must name"});
  cases.back().block.mutable_load()->set_name("arm");
  cases.push_back({Block("iiwa", "arm"), "load", "load.name \"other\" differs from model \"arm\""});
  cases.back().block.mutable_load()->set_path("arm.urdf");
  cases.back().block.mutable_load()->set_name("other");
  for (const Case& k : cases) {
    ArmDriverConfig c;
    std::string field;
    const Status st = ReadArmDriverConfig(k.block, "CONTACTSIM", &c, &field);
    ASSERT_FALSE(st.ok()) << k.block.ShortDebugString();
    EXPECT_EQ(field, k.field) << k.block.ShortDebugString();
    EXPECT_NE(st.message().find(k.says), std::string::npos) << st.message();
  }
}

// Verifies that a bad field in a config file names the file, the line of the
// field and the field.
TEST(ArmDriverConfigTest, ConfigFileErrorNamesLineAndField) {
  const std::string path = testing::WriteTempFile("arm_bad_rate.pbtxt",
                                     "arm_driver {\n  protocol: \"iiwa\"\n  model: \"iiwa\"\n"
                                     "  status_rate_hz: 5000\n}\n");
  proto::ServerConfig config;
  const Status st = LoadServerConfig(path, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(path + ":4: arm_driver: status_rate_hz must be in (0, 1000] Hz"),
            std::string::npos)
      << st.message();
}

// Verifies that the gains take their defaults, spread one value over the
// seven joints or take one per joint, and that gravity compensation is on
// unless the block turns it off.
TEST(ArmDriverConfigTest, GainsAndGravityCompensation) {
  ArmDriverConfig c;
  std::string field;
  proto::ArmDriver block = Block("iiwa", "arm");
  ASSERT_TRUE(ReadArmDriverConfig(block, "CONTACTSIM", &c, &field).ok());
  EXPECT_EQ(c.kp, std::vector<double>(kArmJoints, kDefaultArmKp));
  EXPECT_EQ(c.kd, std::vector<double>(kArmJoints, kDefaultArmKd));
  EXPECT_TRUE(c.gravity_compensation);
  block.add_kp(500);
  for (int i = 0; i < kArmJoints; ++i) block.add_kd(i);
  block.set_gravity_compensation(false);
  ASSERT_TRUE(ReadArmDriverConfig(block, "CONTACTSIM", &c, &field).ok());
  EXPECT_EQ(c.kp, std::vector<double>(kArmJoints, 500));
  EXPECT_EQ(c.kd, (std::vector<double>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_FALSE(c.gravity_compensation);
}

// Verifies that a valid block of either protocol reaches the server's
// options with the protocol's channels.
TEST(ArmDriverConfigTest, IiwaAndPandaBlocksStart) {
  for (const char* protocol : {"iiwa", "panda"}) {
    const std::string path = testing::WriteTempFile(std::string("arm_") + protocol + ".pbtxt",
                                       std::string("arm_driver {\n  protocol: \"") + protocol +
                                           "\"\n  model: \"arm\"\n}\n");
    proto::ServerConfig config;
    const Status loaded = LoadServerConfig(path, &config);
    ASSERT_TRUE(loaded.ok()) << loaded.message();
    ServerSetup setup;
    const Status st = MakeServerSetup(config, path, "", &setup);
    ASSERT_TRUE(st.ok()) << st.message();
    ASSERT_TRUE(setup.options.arm_driver.has_value());
    EXPECT_EQ(setup.options.arm_driver->protocol, protocol);
    EXPECT_EQ(setup.options.arm_driver->command_channel, DefaultArmCommandChannel(protocol));
  }
}

}  // namespace
}  // namespace contactsim
