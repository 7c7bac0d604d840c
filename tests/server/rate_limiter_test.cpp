// Tests of the per-client token buckets.
#include "service/server/rate_limiter.h"

#include <gtest/gtest.h>

namespace contactsim {
namespace {

using Clock = RateLimiter::Clock;
using std::chrono::milliseconds;

int AdmittedOf(RateLimiter* limiter, const std::string& client, int tries, Clock::time_point now) {
  int admitted = 0;
  for (int i = 0; i < tries; ++i) admitted += limiter->Admit(client, now);
  return admitted;
}

// Verifies that a client gets its burst at once, then the rate, and that
// one client's flood leaves another's bucket full.
TEST(RateLimiterTest, BurstThenRatePerClient) {
  RateLimiter limiter(100.0, 10.0);
  const auto t0 = Clock::now();
  EXPECT_EQ(AdmittedOf(&limiter, "flood", 50, t0), 10);
  EXPECT_EQ(AdmittedOf(&limiter, "other", 5, t0), 5);
  EXPECT_EQ(AdmittedOf(&limiter, "flood", 50, t0 + milliseconds(100)), 10);  // 100 /s for 0.1 s
  EXPECT_EQ(AdmittedOf(&limiter, "flood", 50, t0 + milliseconds(150)), 5);
  // a long pause refills to the burst, not beyond
  EXPECT_EQ(AdmittedOf(&limiter, "flood", 50, t0 + milliseconds(60000)), 10);
}

// Verifies that a rate of 0 admits everything.
TEST(RateLimiterTest, ZeroRateMeansNoLimit) {
  RateLimiter limiter(0.0, 1.0);
  EXPECT_EQ(AdmittedOf(&limiter, "a", 1000, Clock::now()), 1000);
}

// Verifies that new client ids cannot outgrow the table or the rate: once
// the table is full, unknown clients share one overflow bucket, and
// refilled buckets make room again.
TEST(RateLimiterTest, InventedClientIdsShareTheOverflowBucket) {
  RateLimiter limiter(10.0, 2.0, /*max_clients=*/4);
  const auto t0 = Clock::now();
  int admitted = 0;
  for (int i = 0; i < 100; ++i) admitted += limiter.Admit("id" + std::to_string(i), t0);
  EXPECT_EQ(limiter.tracked(), 4u);
  EXPECT_EQ(admitted, 4 + 2);  // one each for the four tracked, the overflow's burst of 2
  // a second later every bucket has refilled: the table makes room
  EXPECT_TRUE(limiter.Admit("late", t0 + milliseconds(1000)));
  EXPECT_LE(limiter.tracked(), 4u);
}

}  // namespace
}  // namespace contactsim
