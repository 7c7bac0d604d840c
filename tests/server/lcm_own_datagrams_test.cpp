// Tests of the own-datagram filter (service/server/lcm_own_datagrams.h) on
// real LCM sockets: once installed, an LCM instance no longer hears what it
// publishes itself, and still hears another instance on the same group.
#include "service/server/lcm_own_datagrams.h"

#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>
#include <unistd.h>

#include <string>

namespace contactsim {
namespace {

struct Counter {
  int received = 0;
  static void Handle(const lcm::ReceiveBuffer*, const std::string&, Counter* c) { ++c->received; }
};

// Publishes one byte on `channel` from `from` and lets `to` handle what
// arrives within 300 ms.
void PublishAndHandle(lcm::LCM& from, lcm::LCM& to, const std::string& channel) {
  const char byte = 1;
  from.publish(channel, &byte, 1);
  for (int i = 0; i < 3; ++i) to.handleTimeout(100);
}

// Verifies the URL parsing: the port and ttl of udpm URLs, LCM's default
// ttl 0, and no answer for another provider.
TEST(LcmOwnDatagramsTest, ParsesUdpmUrls) {
  int port = 0, ttl = -1;
  ASSERT_TRUE(ParseUdpmUrl("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608", &port, &ttl));
  EXPECT_EQ(port, 7667);
  EXPECT_EQ(ttl, 0);
  ASSERT_TRUE(ParseUdpmUrl("udpm://239.255.76.67:7700", &port, &ttl));
  EXPECT_EQ(port, 7700);
  EXPECT_EQ(ttl, 0);
  ASSERT_TRUE(ParseUdpmUrl("udpm://239.255.76.67:7701?ttl=1", &port, &ttl));
  EXPECT_EQ(ttl, 1);
  EXPECT_FALSE(ParseUdpmUrl("memq://", &port, &ttl));
}

// Verifies that with the filter an instance does not receive its own
// message (it did before), and still receives another instance's.
TEST(LcmOwnDatagramsTest, OwnDatagramsAreDroppedOthersKept) {
  const int port = 20000 + getpid() % 20000;
  const std::string url = "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0";
  lcm::LCM own(url);
  ASSERT_TRUE(own.good());
  Counter counter;
  own.subscribeFunction("OWN_DATAGRAM_TEST", &Counter::Handle, &counter);
  PublishAndHandle(own, own, "OWN_DATAGRAM_TEST");
  ASSERT_EQ(counter.received, 1) << "LCM's loopback: an instance hears itself";
  const Status st = FilterOwnDatagrams(port);
  ASSERT_TRUE(st.ok()) << st.message();
  PublishAndHandle(own, own, "OWN_DATAGRAM_TEST");
  EXPECT_EQ(counter.received, 1);
  lcm::LCM other(url);
  ASSERT_TRUE(other.good());
  PublishAndHandle(other, own, "OWN_DATAGRAM_TEST");
  EXPECT_EQ(counter.received, 2);
  // two instances: which sockets are whose is no longer clear, so no filter
  Counter other_counter;
  other.subscribeFunction("OWN_DATAGRAM_TEST", &Counter::Handle, &other_counter);
  other.handleTimeout(10);
  EXPECT_EQ(FilterOwnDatagrams(port).code(), StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace contactsim
