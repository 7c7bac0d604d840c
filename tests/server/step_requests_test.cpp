// Tests of the steps the world owes its clients (service/server/step_requests.h):
// the budget, which STEP is done at which step, the text of an interrupted
// STEP, and the PROGRESS each reports.
#include "service/server/step_requests.h"

#include <gtest/gtest.h>

#include <contactsim/progress_t.hpp>

#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

Command Step(const std::string& client, int64_t request_id, int steps) {
  Command c;
  c.kind = Command::Kind::kStep;
  c.client_id = client;
  c.request_id = request_id;
  c.steps = steps;
  return c;
}

struct Fixture {
  testing::RecordingTransport transport;
  ServerOptions options;
  Publisher publisher{options, &transport};
  StepRequests steps{&publisher};
  std::vector<progress_t> Progress() const { return transport.All<progress_t>(publisher.Channel("PROGRESS")); }
};

// Verifies that STEPs queue behind each other: each ends where the budget
// reaches when it is accepted, and is done, oldest first, at its last step.
TEST(StepRequests, StepsEndInOrderWhereTheBudgetReaches) {
  Fixture f;
  f.steps.Add(Step("a", 1, 3), 10);  // steps 11-13
  f.steps.Add(Step("b", 2, 2), 10);  // steps 14-15
  EXPECT_TRUE(f.steps.owed());
  for (int64_t step = 11; step <= 15; ++step) {
    f.steps.Took();
    const std::vector<StepRequests::Request> done = f.steps.Done(step);
    if (step == 13) {
      ASSERT_EQ(done.size(), 1u);
      EXPECT_EQ(done[0].client_id, "a");
    } else if (step == 15) {
      ASSERT_EQ(done.size(), 1u);
      EXPECT_EQ(done[0].request_id, 2);
    } else {
      EXPECT_TRUE(done.empty()) << step;
    }
  }
  EXPECT_FALSE(f.steps.owed());
}

// Verifies that a cancel answers every STEP in flight with how far it got
// and drops the budget.
TEST(StepRequests, CancelSaysHowFarEachStepGot) {
  Fixture f;
  f.steps.Add(Step("a", 1, 4), 0);  // steps 1-4
  f.steps.Add(Step("b", 2, 4), 0);  // steps 5-8
  for (int i = 0; i < 2; ++i) f.steps.Took();
  const std::vector<StepRequests::Answer> answers = f.steps.Cancel("cancelled by PAUSE", 2);
  ASSERT_EQ(answers.size(), 2u);
  EXPECT_EQ(answers[0].status.code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(answers[0].status.message(), "step interrupted: cancelled by PAUSE after 2 of 4 steps (at step 2)");
  EXPECT_EQ(answers[1].status.message(), "step interrupted: cancelled by PAUSE after 0 of 4 steps (at step 2)");
  EXPECT_FALSE(f.steps.owed());
  EXPECT_TRUE(f.steps.Done(100).empty());
}

// Verifies that an accepted STEP reports its progress at once (0 of n), and
// that a forced report gives each STEP's steps done.
TEST(StepRequests, ProgressCountsEachStepsOwnSteps) {
  Fixture f;
  f.steps.Add(Step("a", 7, 5), 20);
  ASSERT_EQ(f.Progress().size(), 1u);
  EXPECT_EQ(f.Progress()[0].command, "STEP");
  EXPECT_EQ(f.Progress()[0].done, 0);
  EXPECT_EQ(f.Progress()[0].total, 5);
  f.steps.ReportProgress(23, true);
  ASSERT_EQ(f.Progress().size(), 2u);
  EXPECT_EQ(f.Progress()[1].done, 3);
  EXPECT_EQ(f.Progress()[1].step, 23);
  EXPECT_EQ(f.Progress()[1].request_id, 7);
}

}  // namespace
}  // namespace contactsim
