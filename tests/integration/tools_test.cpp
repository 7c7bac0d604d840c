// contactsim-ctl and the drop-ball example, run as programs against the
// real server.
#include <string>
#include <vector>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

constexpr std::chrono::milliseconds kProgramTimeout{60000};

class ToolsTest : public ServerTest {
 protected:
  ProcessOutput Ctl(const std::vector<std::string>& args) const {
    std::vector<std::string> argv = {std::string(CONTACTSIM_BIN_DIR) + "/contactsim-ctl",
                                     "--lcm-url", server_.url(), "--prefix",
                                     server_.prefix(), "--timeout", "5"};
    argv.insert(argv.end(), args.begin(), args.end());
    return RunProcess(argv, kProgramTimeout);
  }
};

// Verifies contactsim-ctl prints the status, adds a sphere (printing its
// id), steps, and exits non-zero on an error reply.
TEST_F(ToolsTest, CtlStatusAddAndStep) {
  const ProcessOutput status = Ctl({"status"});
  ASSERT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find("paused: yes"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("mode: free_run"), std::string::npos) << status.output;

  const ProcessOutput add =
      Ctl({"add", "sphere", "--radius", "0.1", "--position", "0", "0", "1", "--mass", "2"});
  ASSERT_EQ(add.exit_code, 0) << add.output;
  EXPECT_NE(add.output.find("OK"), std::string::npos) << add.output;
  EXPECT_NE(add.output.find("ids=["), std::string::npos) << add.output;

  const ProcessOutput step = Ctl({"step", "10"});
  ASSERT_EQ(step.exit_code, 0) << step.output;
  EXPECT_NE(step.output.find("step=10"), std::string::npos) << step.output;
  // The sphere the CLI added is really in the world.
  const std::optional<state_t> state = client_->WaitForState(
      [](const state_t& s) { return s.step >= 10; }, kReplyTimeout);
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->num_bodies, 1);

  const ProcessOutput remove = Ctl({"remove", "4242"});
  EXPECT_EQ(remove.exit_code, 1) << remove.output;
  EXPECT_NE(remove.output.find("NOT_FOUND"), std::string::npos) << remove.output;
}

// Verifies contactsim-ctl gives up with exit status 2 when no server answers.
TEST_F(ToolsTest, CtlWithoutServerTimesOut) {
  const ProcessOutput pause = RunProcess(
      {std::string(CONTACTSIM_BIN_DIR) + "/contactsim-ctl", "--lcm-url", server_.url(),
       "--prefix", server_.prefix() + "_NOBODY", "--timeout", "0.2", "pause"},
      kProgramTimeout);
  EXPECT_EQ(pause.exit_code, 2) << pause.output;
  EXPECT_NE(pause.output.find("TIMEOUT"), std::string::npos) << pause.output;
}

// Verifies the drop-ball example runs to the end and prints a bounce apex.
TEST_F(ToolsTest, DropBallExamplePrintsBounces) {
  const ProcessOutput example = RunProcess(
      {std::string(CONTACTSIM_BIN_DIR) + "/contactsim-example-drop-ball", "--lcm-url",
       server_.url(), "--prefix", server_.prefix(), "--seconds", "1.5"},
      kProgramTimeout);
  ASSERT_EQ(example.exit_code, 0) << example.output;
  EXPECT_NE(example.output.find("bounce 1: apex"), std::string::npos) << example.output;
}

}  // namespace
}  // namespace contactsim::testing
