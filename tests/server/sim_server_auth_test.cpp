// Tests of the server's receive path with a key: only signed, fresh, new
// commands reach the world; every refusal names its sender and its reason,
// is counted, and changes nothing; the journal keeps the bare command.
#include <gtest/gtest.h>

#include <contactsim/signature.h>
#include <contactsim/status_t.hpp>

#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

const std::string kServerKey(64, 'k');

ServerOptions Signed() {
  ServerOptions o;
  o.prefix = "A";
  o.auth_key = kServerKey;
  return o;
}

std::string Bytes(const body_cmd_t& m) {
  const auto v = testing::Encode(m);
  return std::string(v.begin(), v.end());
}

reply_t Deliver(ServerHarness& h, const std::string& bytes) {
  h.server.OnMessage(h.server.Channel("BODY_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  h.server.Tick();
  return h.transport.All<reply_t>(h.server.Channel("REPLY")).back();
}

// Verifies the four refusals (unsigned, forged, stale, replayed) and that a
// signed command from the same client is applied.
TEST(SimServerAuthTest, OnlySignedFreshNewCommandsAreApplied) {
  ServerHarness h(Signed());
  Signer signer(kServerKey), forger(std::string(64, 'x'));
  const std::string channel = h.server.Channel("BODY_CMD");
  body_cmd_t add = h.Box(0.1, Vec3(0, 0, 1));
  add.request_id = 1;
  const std::string bare = Bytes(add);

  reply_t r = Deliver(h, bare);
  EXPECT_EQ(r.code, reply_t::UNAUTHENTICATED);
  EXPECT_EQ(r.request_id, 1);  // the sender still hears why
  EXPECT_NE(r.message.find("must be signed"), std::string::npos) << r.message;

  r = Deliver(h, forger.Sign(channel, bare.data(), static_cast<int>(bare.size())));
  EXPECT_EQ(r.code, reply_t::UNAUTHENTICATED);
  EXPECT_NE(r.message.find("forged"), std::string::npos) << r.message;

  const uint64_t old = WallClockNanoseconds() - uint64_t{100} * 1000000000;
  r = Deliver(h, bare + SignatureTrailer(kServerKey, channel, bare.data(), static_cast<int>(bare.size()), old));
  EXPECT_EQ(r.code, reply_t::UNAUTHENTICATED);
  EXPECT_NE(r.message.find("stale"), std::string::npos) << r.message;
  EXPECT_EQ(h.server.world().bodies().size(), 0u);

  const std::string good = signer.Sign(channel, bare.data(), static_cast<int>(bare.size()));
  r = Deliver(h, good);
  EXPECT_EQ(r.code, reply_t::OK) << r.message;
  r = Deliver(h, good);
  EXPECT_EQ(r.code, reply_t::UNAUTHENTICATED);
  EXPECT_NE(r.message.find("replayed"), std::string::npos) << r.message;
  EXPECT_EQ(h.server.world().bodies().size(), 1u);
}

// Verifies that a server without a key takes a signed command (the trailer
// cut off unread), so a signing client still works against it.
TEST(SimServerAuthTest, AServerWithoutAKeyCutsTheTrailerOff) {
  ServerOptions o;
  o.prefix = "A";
  ServerHarness h(o);
  Signer signer(kServerKey);
  body_cmd_t add = h.Box(0.1, Vec3(0, 0, 1));
  const std::string bare = Bytes(add);
  const reply_t r = Deliver(h, signer.Sign(h.server.Channel("BODY_CMD"), bare.data(), static_cast<int>(bare.size())));
  EXPECT_EQ(r.code, reply_t::OK) << r.message;
}

}  // namespace
}  // namespace contactsim
