// STEP n semantics (docs/protocol.md) on the real server.
#include <chrono>
#include <cmath>
#include <thread>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using StepTest = ServerTest;

// Verifies STEP n takes exactly n steps, replies with the last step's index
// and time, and that Step() returns only once that STATE has arrived.
TEST_F(StepTest, StepTakesExactlyNStepsAndPublishesTheLastState) {
  const CommandResult first = client_->Step(1);
  ASSERT_TRUE(first.ok()) << first;
  const CommandResult tenth = client_->Step(10);
  ASSERT_TRUE(tenth.ok()) << tenth;
  EXPECT_EQ(tenth.step, first.step + 10);

  const std::optional<state_t> state = client_->LatestState();
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->step, tenth.step);
  EXPECT_DOUBLE_EQ(state->time, tenth.time);
  const std::optional<status_t> status = client_->LatestStatus();
  ASSERT_TRUE(status.has_value());
  ASSERT_GT(status->dt, 0.0);
  // Time is step * dt up to the round-off of summing dt step by step.
  EXPECT_NEAR(tenth.time, tenth.step * status->dt, 1e-9 * tenth.step);
}

// Verifies STEP on a running world pauses it: nothing moves between two
// STEP commands, however long we wait.
TEST_F(StepTest, StepLeavesTheRunPaused) {
  // Realtime, not free-run: a free-running empty world takes ~10^5 steps/s
  // and publishes a STATE every few of them, a flood in which the kernel
  // drops datagrams, the last STEP's STATE among them.
  ASSERT_TRUE(client_->SetMode(Mode::kRealtime, 1.0).ok());
  ASSERT_TRUE(client_->Resume().ok());
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const CommandResult step = client_->Step(5);
  ASSERT_TRUE(step.ok()) << step;
  // Had the run gone on, 300 ms would be ~70 steps at 240 steps/s.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const CommandResult next = client_->Step(1);
  ASSERT_TRUE(next.ok()) << next;
  EXPECT_EQ(next.step, step.step + 1);
}

// Verifies STEP with n < 1 is rejected naming "steps" and takes no step.
TEST_F(StepTest, NonPositiveStepCountIsRejected) {
  const CommandResult before = client_->Step(2);
  ASSERT_TRUE(before.ok()) << before;
  for (int32_t n : {0, -3}) {
    const CommandResult result = client_->Step(n);
    EXPECT_EQ(ReplyCodeName(result.code), "INVALID_ARGUMENT") << result;
    EXPECT_NE(result.message.find("steps"), std::string::npos) << result.message;
  }
  const CommandResult after = client_->Step(1);
  ASSERT_TRUE(after.ok()) << after;
  EXPECT_EQ(after.step, before.step + 1);
}

// Verifies a command sent while paused takes effect at the current step:
// its reply carries the index and time of the last STATE.
TEST_F(StepTest, ReplyCarriesTheStepAtWhichTheCommandTookEffect) {
  const CommandResult step = client_->Step(7);
  ASSERT_TRUE(step.ok()) << step;
  const Result<int64_t> added = client_->AddSphere(0.1);
  ASSERT_TRUE(added.ok()) << added.status;
  EXPECT_EQ(added.status.step, step.step);
  EXPECT_DOUBLE_EQ(added.status.time, step.time);
}

// Verifies a new body appears in the next STATE with the pose it was given.
TEST_F(StepTest, AddedBodyAppearsInTheNextState) {
  BodyOptions options;
  options.position = {0.5, -0.25, 2.0};
  const Result<int64_t> added = client_->AddSphere(0.1, options);
  ASSERT_TRUE(added.ok()) << added.status;
  ASSERT_TRUE(client_->Step(1).ok());
  const std::optional<state_t> state = client_->LatestState();
  ASSERT_TRUE(state.has_value());
  ASSERT_EQ(state->num_bodies, 1);
  EXPECT_EQ(state->bodies[0].id, added.value);
  EXPECT_DOUBLE_EQ(state->bodies[0].position[0], 0.5);
  EXPECT_DOUBLE_EQ(state->bodies[0].position[1], -0.25);
  // One step of free fall from rest: z drops by at most g dt^2.
  EXPECT_LT(state->bodies[0].position[2], 2.0);
  EXPECT_GT(state->bodies[0].position[2], 2.0 - 9.81 * 0.1 * 0.1);
}

}  // namespace
}  // namespace contactsim::testing
