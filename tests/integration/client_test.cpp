// contactsim::Client behaviour that only a real server can show: reply
// matching between clients, callbacks, waiting for states, timeouts.
#include <atomic>
#include <set>
#include <thread>
#include <vector>

#include "server_fixture.h"

namespace contactsim::testing {
namespace {

using ClientTest = ServerTest;

// Verifies two Clients of one process get distinct client ids and each
// receives exactly its own replies while both send at the same time.
TEST_F(ClientTest, ConcurrentClientsGetTheirOwnReplies) {
  constexpr int kBodiesPerClient = 20;
  std::unique_ptr<Client> other = server_.NewClient();
  ASSERT_NE(client_->client_id(), other->client_id());

  std::vector<int64_t> ids_a, ids_b;
  std::thread a([&] {
    for (int i = 0; i < kBodiesPerClient; ++i) {
      const Result<int64_t> added = client_->AddSphere(0.1);
      if (added.ok()) ids_a.push_back(added.value);
    }
  });
  std::thread b([&] {
    for (int i = 0; i < kBodiesPerClient; ++i) {
      const Result<int64_t> added = other->AddBox({0.1, 0.1, 0.1});
      if (added.ok()) ids_b.push_back(added.value);
    }
  });
  a.join();
  b.join();
  ASSERT_EQ(ids_a.size(), static_cast<size_t>(kBodiesPerClient));
  ASSERT_EQ(ids_b.size(), static_cast<size_t>(kBodiesPerClient));
  std::set<int64_t> all(ids_a.begin(), ids_a.end());
  all.insert(ids_b.begin(), ids_b.end());
  EXPECT_EQ(all.size(), static_cast<size_t>(2 * kBodiesPerClient))
      << "a body id was handed to both clients: replies were crossed";

  ASSERT_TRUE(client_->Step(1).ok());
  EXPECT_EQ(client_->LatestState()->num_bodies, 2 * kBodiesPerClient);
}

// Verifies OnState sees the STATE of every STEP command, and WaitForState
// returns a state matching its predicate.
TEST_F(ClientTest, StateCallbacksAndWaitForState) {
  std::atomic<int64_t> last_step{-1};
  std::atomic<int> calls{0};
  const int callback = client_->OnState([&](const state_t& state) {
    last_step = state.step;
    ++calls;
  });
  const CommandResult step = client_->Step(4);
  ASSERT_TRUE(step.ok()) << step;
  // Step returns once the state is in LatestState; the callback ran first.
  EXPECT_EQ(last_step.load(), step.step);
  EXPECT_GE(calls.load(), 1);
  client_->RemoveCallback(callback);

  const std::optional<state_t> found = client_->WaitForState(
      [&](const state_t& s) { return s.step == step.step; }, kReplyTimeout);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->step, step.step);
  // Nothing steps a paused server, so no later state can match.
  EXPECT_FALSE(client_
                   ->WaitForState([&](const state_t& s) { return s.step > step.step; },
                                  std::chrono::milliseconds(200))
                   .has_value());
}

// Verifies a command nobody answers comes back as kTimeout, not a hang.
TEST_F(ClientTest, UnansweredCommandTimesOut) {
  ClientOptions options;
  options.url = server_.url();
  options.prefix = server_.prefix() + "_NOBODY";
  options.reply_timeout = std::chrono::milliseconds(200);
  Client lonely(options);
  const CommandResult result = lonely.Pause();
  EXPECT_EQ(ReplyCodeName(result.code), "TIMEOUT") << result;
  EXPECT_FALSE(lonely.WaitForServer(std::chrono::milliseconds(100)));
}

}  // namespace
}  // namespace contactsim::testing
