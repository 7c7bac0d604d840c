// Tests of server configuration files.
#include "service/server/server_config.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "service/collision/parallel_runner.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

// Verifies that the shipped default config loads with its scene.
TEST(ServerConfig, DefaultConfigLoads) {
  const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/server.pbtxt";
  proto::ServerConfig config;
  ASSERT_TRUE(LoadServerConfig(path, &config).ok());
  ServerSetup setup;
  const Status st = MakeServerSetup(config, path, "", &setup);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_NE(setup.scene, nullptr);
  EXPECT_EQ(std::string(setup.method->Name()), "impulse");
  EXPECT_EQ(setup.options.prefix, "CONTACTSIM");
}

// Verifies that a bad value names the file, the line and the field.
TEST(ServerConfig, BadValueNamesFileLineAndField) {
  const std::string path = testing::WriteTempFile("bad_rate.pbtxt", "channel_prefix: \"X\"\nstate_rate_hz: -5\n");
  proto::ServerConfig config;
  const Status st = LoadServerConfig(path, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(path + ":2: state_rate_hz must be in"), std::string::npos) << st.message();
}

// Verifies that lockstep_step_on_input is on unless the config turns it
// off, and that a value that is not a bool is refused by the text format's
// parser, which names the file and the line.
TEST(ServerConfig, LockstepStepOnInputIsReadAndABadValueRefused) {
  EXPECT_TRUE(ServerOptions{}.lockstep_step_on_input);
  proto::ServerConfig config;
  const std::string off = testing::WriteTempFile("lockstep_off.pbtxt", "lockstep_step_on_input: false\n");
  ASSERT_TRUE(LoadServerConfig(off, &config).ok());
  ServerSetup setup;
  ASSERT_TRUE(MakeServerSetup(config, off, "", &setup).ok());
  EXPECT_FALSE(setup.options.lockstep_step_on_input);
  for (const char* bad : {"lockstep_step_on_input: 2\n", "lockstep_step_on_input: \"yes\"\n"}) {
    const std::string path = testing::WriteTempFile("lockstep_bad.pbtxt", std::string("mode: LOCKSTEP\n") + bad);
    const Status st = LoadServerConfig(path, &config);
    ASSERT_FALSE(st.ok()) << bad;
    EXPECT_NE(st.message().find(path + ":2:"), std::string::npos) << st.message();
  }
}

// Verifies that an unknown contact method in the config is refused.
TEST(ServerConfig, UnknownMethodIsRefused) {
  const std::string path = testing::WriteTempFile("bad_method.pbtxt", "contact_method: \"magic\"\n");
  proto::ServerConfig config;
  const Status st = LoadServerConfig(path, &config);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find(":1: unknown contact method \"magic\""), std::string::npos) << st.message();
}

// Verifies that a missing scene file is reported with its path.
TEST(ServerConfig, MissingSceneIsReported) {
  const std::string path = testing::WriteTempFile("missing_scene.pbtxt", "scene: \"nowhere.pbtxt\"\n");
  proto::ServerConfig config;
  ASSERT_TRUE(LoadServerConfig(path, &config).ok());
  ServerSetup setup;
  const Status st = MakeServerSetup(config, path, "", &setup);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("nowhere.pbtxt: cannot open file"), std::string::npos) << st.message();
}

// The server options a config of `text` gives (a failure fails the test).
ServerOptions OptionsOf(const std::string& text) {
  const std::string path = testing::WriteTempFile("options.pbtxt", text);
  proto::ServerConfig config;
  const Status loaded = LoadServerConfig(path, &config);
  EXPECT_TRUE(loaded.ok()) << loaded.message();
  ServerSetup setup;
  const Status st = MakeServerSetup(config, path, "", &setup);
  EXPECT_TRUE(st.ok()) << st.message();
  return setup.options;
}

// Verifies that `threads` defaults to the machine's hardware threads and
// that a given count reaches the server's options.
TEST(ServerConfig, ThreadsDefaultToTheMachineAndAreTaken) {
  for (const auto& [text, expected] : {std::pair<std::string, int>{"", DefaultThreadCount()}, {"threads: 1\n", 1},
                                       {"threads: 3\n", 3}}) {
    EXPECT_EQ(OptionsOf(text).threads, expected) << text;
  }
}

// Verifies that `sleep` defaults to on (as in Box2D, Bullet and Jolt) and
// that `sleep: false` reaches the server's options.
TEST(ServerConfig, SleepDefaultsToOnAndIsTaken) {
  for (const auto& [text, expected] : {std::pair<std::string, bool>{"", true}, {"sleep: false\n", false},
                                       {"sleep: true\n", true}}) {
    EXPECT_EQ(OptionsOf(text).sleep, expected) << text;
  }
}

// Verifies that zero, negative and absurd thread counts are refused with
// the file, the line, the field and the value.
TEST(ServerConfig, BadThreadCountsAreRefusedNamingTheValue) {
  for (const std::string value : {"0", "-2", "100000"}) {
    const std::string path = testing::WriteTempFile("bad_threads.pbtxt", "channel_prefix: \"X\"\nthreads: " + value + "\n");
    proto::ServerConfig config;
    const Status st = LoadServerConfig(path, &config);
    ASSERT_FALSE(st.ok()) << value;
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
    EXPECT_NE(st.message().find(path + ":2: threads must be between 1 and 256, got " + value), std::string::npos)
        << st.message();
  }
}

}  // namespace
}  // namespace contactsim
