// Lockstep co-simulation end to end: the real server and the PD example
// (clients/cpp/examples/pd_hover.cpp) as two processes.
#include <gtest/gtest.h>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using LockstepTest = ServerTest;

// Verifies that the example's PD controller, sending forces in lockstep,
// settles the box within 1 cm of the target height (the example's own exit
// criterion) after the steps it asked for.
TEST_F(LockstepTest, PdExampleHoldsTheBoxAtTheTargetHeight) {
  const ProcessOutput out =
      RunProcess({CONTACTSIM_BIN_DIR "/contactsim-example-pd-hover", "--lcm-url", server_.url(), "--prefix",
                  server_.prefix(), "--seconds", "2", "--target", "0.4"},
                 std::chrono::seconds(120));
  EXPECT_EQ(out.exit_code, 0) << out.output;
  // STEP 480 in lockstep ends the run at step 480 exactly
  EXPECT_NE(out.output.find("final: step 480 "), std::string::npos) << out.output;
  EXPECT_TRUE(client_->WaitForState([](const state_t& s) { return s.step == 480; }, kReplyTimeout).has_value());
}

}  // namespace
}  // namespace contactsim::testing
