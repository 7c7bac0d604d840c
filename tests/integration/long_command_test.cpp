// Long commands on the real server (docs/protocol.md, "Long commands"): a
// STEP longer than the client's reply timeout returns, with progress
// reports, and PAUSE from another client stops it.
#include <algorithm>
#include <atomic>
#include <thread>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using LongCommandTest = ServerTest;

// Verifies that Step waits past reply_timeout while the server reports
// progress, and hands each report to the callback.
TEST_F(LongCommandTest, StepOutlastsTheReplyTimeoutWhileProgressComes) {
  ASSERT_TRUE(client_->LoadScene(std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/box_pyramid.pbtxt").ok());
  ASSERT_TRUE(client_->SetContactMethod("xpbd").ok());
  // a timeout a few steps long and a STEP several timeouts long, whatever
  // this build and machine make of a step: measured by a patient client, as
  // progress comes between steps and one xpbd step of the pyramid can take
  // longer than the fixture's reply timeout under the sanitizers
  ClientOptions options;
  options.url = server_.url();
  options.prefix = server_.prefix();
  options.reply_timeout = std::chrono::minutes(2);
  Client patient(options);
  ASSERT_TRUE(patient.Step(2).ok());  // the first steps build the contacts and cost more
  auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(patient.Step(4).ok());
  const double per_step = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / 4;
  const double timeout = std::max(0.3, 4 * per_step);
  options.reply_timeout = std::chrono::milliseconds(static_cast<int64_t>(timeout * 1000));
  Client impatient(options);
  // steps get cheaper as the pyramid settles, so a STEP that came back
  // inside the timeout is retried twice as long until one outlasts it
  int64_t steps = 6;
  std::vector<int64_t> done;
  bool outlasted = false;
  for (int n = static_cast<int>(4 * timeout / per_step) + 1; !outlasted && n < 1000000; n *= 2) {
    done.clear();
    t0 = std::chrono::steady_clock::now();
    const CommandResult r = impatient.Step(n, [&](const progress_t& p) {
      EXPECT_EQ(p.total, n);
      done.push_back(p.done);
    });
    ASSERT_TRUE(r.ok()) << r;
    steps += n;
    EXPECT_EQ(r.step, steps);
    outlasted = std::chrono::steady_clock::now() - t0 > options.reply_timeout;
  }
  ASSERT_TRUE(outlasted) << "no STEP outlasted the reply timeout";
  ASSERT_FALSE(done.empty());
  EXPECT_EQ(done.front(), 0);
  EXPECT_TRUE(std::is_sorted(done.begin(), done.end()));
}

// Verifies that PAUSE stops a running STEP and its reply says how far it got.
TEST_F(LongCommandTest, PauseStopsARunningStep) {
  BodyOptions ball;
  ball.position = Eigen::Vector3d(0, 0, 0.5);
  ASSERT_TRUE(client_->AddSphere(0.05, ball).ok());
  std::unique_ptr<Client> stepper = server_.NewClient();
  std::atomic<bool> started{false};
  CommandResult result;
  std::thread t([&] { result = stepper->Step(100000000, [&](const progress_t&) { started = true; }); });
  for (int i = 0; i < 1000 && !started; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(started.load());
  ASSERT_TRUE(client_->Pause().ok());
  t.join();
  EXPECT_EQ(result.code, ReplyCode::kFailedPrecondition);
  EXPECT_NE(result.message.find("cancelled by PAUSE"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("of 100000000 steps"), std::string::npos) << result.message;
  EXPECT_GT(result.step, 0);
}

}  // namespace
}  // namespace contactsim::testing
