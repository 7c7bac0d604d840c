// Tests of the server config's arm_driver block: Drake's defaults fill
// absent fields, each bad field is refused with its name and line, and a
// valid block is refused at start while the server has no arm driver.
#include "service/server/arm_driver/arm_driver_config.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <vector>

#include "service/server/server_config.h"

namespace contactsim {
namespace {

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

proto::ArmDriver Block(const std::string& protocol, const std::string& model) {
  proto::ArmDriver b;
  b.set_protocol(protocol);
  b.set_model(model);
  return b;
}

// Verifies that each protocol takes the channel names of Drake's driver and
// the 200 Hz status rate when the block leaves them out.
TEST(ArmDriverConfigTest, AbsentFieldsTakeDrakesDefaults) {
  for (const char* protocol : {"iiwa", "panda"}) {
    ArmDriverConfig c;
    std::string field;
    ASSERT_TRUE(ReadArmDriverConfig(Block(protocol, "arm"), "CONTACTSIM", &c, &field).ok()) << protocol;
    EXPECT_EQ(c.model, "arm");
    EXPECT_DOUBLE_EQ(c.status_rate_hz, 200.0);
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
  const std::string path = WriteTemp("arm_bad_rate.pbtxt",
                                     "arm_driver {\n  protocol: \"iiwa\"\n  model: \"iiwa\"\n"
                                     "  status_rate_hz: 5000\n}\n");
  proto::ServerConfig config;
  const Status st = LoadServerConfig(path, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(path + ":4: arm_driver: status_rate_hz must be in (0, 1000] Hz"),
            std::string::npos)
      << st.message();
}

// Verifies that a valid block passes the file's checks but the server does
// not start with it, saying that this server cannot serve the protocol.
TEST(ArmDriverConfigTest, ValidBlockIsRefusedAtStart) {
  const std::string path = WriteTemp("arm_ok.pbtxt", "arm_driver {\n  protocol: \"iiwa\"\n  model: \"iiwa\"\n}\n");
  proto::ServerConfig config;
  const Status loaded = LoadServerConfig(path, &config);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ServerSetup setup;
  const Status st = MakeServerSetup(config, path, "", &setup);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("arm_driver: this contactsim-server does not serve Drake's arm-driver protocol"),
            std::string::npos)
      << st.message();
}

}  // namespace
}  // namespace contactsim
