// Tests of the server config's wsg_driver block: Drake's defaults fill
// absent fields, each bad field is refused with its name (and in a file,
// its line), a channel shared with the arm driver is refused, and a valid
// block beside an arm_driver reaches the server's options.
#include "service/server/arm_driver/wsg_driver_config.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <vector>

#include "service/server/server_config.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

proto::WsgDriver Block() {
  proto::WsgDriver b;
  b.set_model("wsg");
  b.add_finger_joints("left_finger_sliding_joint");
  b.add_finger_joints("right_finger_sliding_joint");
  return b;
}

// Verifies that an absent field takes Drake's: the channels SCHUNK_WSG_COMMAND
// and SCHUNK_WSG_STATUS, 20 Hz (kSchunkWsgLcmStatusPeriod = 0.05 s), the kp
// of SchunkWsgDriver (7200 N/m) and the damping that bounds the fingers'
// speed (400 N s/m, wsg_driver_config.h).
TEST(WsgDriverConfigTest, AbsentFieldsTakeDrakesDefaults) {
  WsgDriverConfig c;
  std::string field;
  ASSERT_TRUE(ReadWsgDriverConfig(Block(), "CONTACTSIM", &c, &field).ok());
  EXPECT_EQ(c.model, "wsg");
  EXPECT_EQ(c.finger_joints[0], "left_finger_sliding_joint");
  EXPECT_EQ(c.finger_joints[1], "right_finger_sliding_joint");
  EXPECT_EQ(c.command_channel, "SCHUNK_WSG_COMMAND");
  EXPECT_EQ(c.status_channel, "SCHUNK_WSG_STATUS");
  EXPECT_DOUBLE_EQ(c.status_rate_hz, 20.0);
  EXPECT_EQ(c.kp, 7200.0);
  EXPECT_EQ(c.kd, 400.0);
  EXPECT_FALSE(c.load.has_value());
}

// Verifies that every bad value is refused and names its field.
TEST(WsgDriverConfigTest, BadValuesNameTheirField) {
  struct Case {
    proto::WsgDriver block;
    const char* field;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({Block(), "model", "model must name"});
  cases.back().block.clear_model();
  cases.push_back({Block(), "finger_joints", "got 1 names"});
  cases.back().block.mutable_finger_joints()->RemoveLast();
  cases.push_back({Block(), "finger_joints", "two different names"});
  cases.back().block.set_finger_joints(1, "left_finger_sliding_joint");
  cases.push_back({Block(), "command_channel", "printable"});
  cases.back().block.set_command_channel("HAS SPACE");
  cases.push_back({Block(), "status_channel", "among the server's own channels"});
  cases.back().block.set_status_channel("CONTACTSIM_STATUS");
  cases.push_back({Block(), "status_channel", "both \"X\""});
  cases.back().block.set_command_channel("X");
  cases.back().block.set_status_channel("X");
  for (double bad : {0.0, -1.0, 2000.0, std::numeric_limits<double>::quiet_NaN()}) {
    cases.push_back({Block(), "status_rate_hz", "(0, 1000] Hz"});
    cases.back().block.set_status_rate_hz(bad);
  }
  cases.push_back({Block(), "kp", "kp must be finite and >= 0, got -1"});
  cases.back().block.set_kp(-1);
  cases.push_back({Block(), "kd", "kd must be finite and >= 0, got inf"});
  cases.back().block.set_kd(std::numeric_limits<double>::infinity());
  cases.push_back({Block(), "load", "load.path"});
  cases.back().block.mutable_load();
  for (const Case& k : cases) {
    WsgDriverConfig c;
    std::string field;
    const Status st = ReadWsgDriverConfig(k.block, "CONTACTSIM", &c, &field);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << k.says;
    EXPECT_EQ(field, k.field) << st.message();
    EXPECT_NE(st.message().find(k.says), std::string::npos) << st.message();
  }
}

// Verifies that a file's bad field is named with its line, and that the
// gripper may not take one of the arm driver's channels.
TEST(WsgDriverConfigTest, ConfigFileErrorNamesLineAndField) {
  const std::string path = testing::WriteTempFile("wsg_bad_kp.pbtxt",
                                     "wsg_driver {\n  model: \"wsg\"\n  finger_joints: \"a\"\n"
                                     "  finger_joints: \"b\"\n  kp: -3\n}\n");
  proto::ServerConfig config;
  Status st = LoadServerConfig(path, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(path + ":5: wsg_driver: kp must be finite and >= 0"), std::string::npos)
      << st.message();
  const std::string clash = testing::WriteTempFile("wsg_clash.pbtxt",
                                      "arm_driver {\n  protocol: \"iiwa\"\n  model: \"iiwa\"\n}\n"
                                      "wsg_driver {\n  model: \"wsg\"\n  finger_joints: \"a\"\n"
                                      "  finger_joints: \"b\"\n  status_channel: \"IIWA_STATUS\"\n}\n");
  st = LoadServerConfig(clash, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(":9: wsg_driver: status_channel \"IIWA_STATUS\" is also one of arm_driver's "
                              "channels"),
            std::string::npos)
      << st.message();
}

// Verifies that a valid block beside an arm_driver reaches the server's
// options with Drake's channels.
TEST(WsgDriverConfigTest, BlockBesideAnArmStarts) {
  const std::string path = testing::WriteTempFile("wsg_and_arm.pbtxt",
                                     "arm_driver {\n  protocol: \"panda\"\n  model: \"panda\"\n}\n"
                                     "wsg_driver {\n  model: \"panda\"\n  finger_joints: \"a\"\n"
                                     "  finger_joints: \"b\"\n}\n");
  proto::ServerConfig config;
  const Status loaded = LoadServerConfig(path, &config);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ServerSetup setup;
  const Status st = MakeServerSetup(config, path, "", &setup);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_TRUE(setup.options.wsg_driver.has_value());
  EXPECT_EQ(setup.options.wsg_driver->command_channel, "SCHUNK_WSG_COMMAND");
  EXPECT_EQ(setup.options.wsg_driver->finger_joints[1], "b");
  EXPECT_TRUE(setup.options.arm_driver.has_value());
}

}  // namespace
}  // namespace contactsim
