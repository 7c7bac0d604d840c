// SigningTransport (service/server/signing_transport.h): what reaches the
// inner transport is the payload plus a trailer that verifies on its channel.
#include "service/server/signing_transport.h"

#include <gtest/gtest.h>

#include <contactsim/signature.h>

#include <string>

#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

const std::string kShortKey(32, 'k');

// Verifies that each published message is signed for its own channel and
// that the seq increases across channels.
TEST(SigningTransportTest, SignsEveryMessageForItsChannel) {
  testing::RecordingTransport inner;
  SigningTransport transport(&inner, kShortKey);
  const std::string state = "state payload";
  transport.Publish("P_STATE", state.data(), static_cast<int>(state.size()));
  transport.Publish("P_REPLY", "r", 1);
  ASSERT_EQ(inner.messages.size(), 2u);
  const auto& [channel, bytes] = inner.messages[0];
  EXPECT_EQ(channel, "P_STATE");
  const Verified first = VerifySignature(kShortKey, channel, bytes.data(), static_cast<int>(bytes.size()));
  ASSERT_TRUE(first.ok) << first.error;
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + first.payload_size), state);
  const auto& reply = inner.messages[1].second;
  const Verified second = VerifySignature(kShortKey, "P_REPLY", reply.data(), static_cast<int>(reply.size()));
  ASSERT_TRUE(second.ok) << second.error;
  EXPECT_GT(second.seq, first.seq);
  EXPECT_FALSE(VerifySignature(kShortKey, "P_STATE", reply.data(), static_cast<int>(reply.size())).ok);
}

// Verifies that a receiver without the key still decodes the payload: the
// trailer only follows it.
TEST(SigningTransportTest, PayloadStaysDecodableWithoutTheKey) {
  testing::RecordingTransport inner;
  SigningTransport transport(&inner, kShortKey);
  const std::string payload = "abc";
  transport.Publish("P_STATUS", payload.data(), 3);
  const auto& bytes = inner.messages[0].second;
  EXPECT_EQ(UnsignedSize(bytes.data(), static_cast<int>(bytes.size())), 3);
}

}  // namespace
}  // namespace contactsim
