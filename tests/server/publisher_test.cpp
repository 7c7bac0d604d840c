// Tests of what the server sends (service/server/publisher.h): the channel
// names, STATE and CONTACTS decimated to their rates of simulated time, and
// STATUS's rates measured between two of them.
#include "service/server/publisher.h"

#include <gtest/gtest.h>

#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

// Verifies that every outgoing channel carries the prefix.
TEST(Publisher, ChannelsCarryThePrefix) {
  testing::RecordingTransport transport;
  ServerOptions o;
  o.prefix = "X";
  Publisher p(o, &transport);
  EXPECT_EQ(p.Channel("STATE"), "X_STATE");
  reply_t r{};
  p.Reply(r);
  ASSERT_EQ(transport.messages.size(), 1u);
  EXPECT_EQ(transport.messages[0].first, "X_REPLY");
}

// Verifies the decimation: at dt = 1/240 s, 60 Hz of STATE is every 4th
// step and 30 Hz of CONTACTS every 8th; 0 Hz is every step.
TEST(Publisher, RatesOfSimulatedTimeBecomeStepsBetweenMessages) {
  testing::RecordingTransport transport;
  ServerOptions o;  // 60 and 30 Hz
  Publisher p(o, &transport);
  p.UpdateRates(1.0 / 240.0);
  EXPECT_TRUE(p.StateDue(8));
  EXPECT_FALSE(p.StateDue(6));
  EXPECT_TRUE(p.ContactsDue(16));
  EXPECT_FALSE(p.ContactsDue(12));
  o.state_rate_hz = 0.0;
  Publisher every(o, &transport);
  every.UpdateRates(1.0 / 240.0);
  EXPECT_TRUE(every.StateDue(7));
}

// Verifies that STATUS measures the step rate and real-time factor over
// the time between two STATUS messages, and that the first one sets only
// the base.
TEST(Publisher, StatusMeasuresRatesBetweenTwoMessages) {
  testing::RecordingTransport transport;
  Publisher p(ServerOptions{}, &transport);
  const auto t0 = Publisher::Clock::now();
  status_t s{};
  s.step = 100;
  s.time = 1.0;
  p.Status(s, t0);
  s.step = 340;
  s.time = 2.0;
  p.Status(s, t0 + std::chrono::seconds(2));
  const std::vector<status_t> sent = transport.All<status_t>(p.Channel("STATUS"));
  ASSERT_EQ(sent.size(), 2u);
  EXPECT_EQ(sent[0].step_rate, 0.0);
  EXPECT_DOUBLE_EQ(sent[1].step_rate, 120.0);        // 240 steps in 2 s
  EXPECT_DOUBLE_EQ(sent[1].real_time_factor, 0.5);  // 1 s of sim time in 2 s
}

// Verifies that a STATE remembers its step, which STEP replies and the
// lockstep wait ask about.
TEST(Publisher, StateRemembersItsStep) {
  testing::RecordingTransport transport;
  Publisher p(ServerOptions{}, &transport);
  World world;
  world.step = 5;
  EXPECT_FALSE(p.StateSentAt(5));
  p.State(world, 0);
  EXPECT_TRUE(p.StateSentAt(5));
  EXPECT_EQ(transport.All<state_t>(p.Channel("STATE")).size(), 1u);
}

}  // namespace
}  // namespace contactsim
