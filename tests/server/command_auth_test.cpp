// The server's gate for signed commands (service/server/command_auth.h):
// each check refuses with a message naming it, and a good command passes
// with its payload size and seq.
#include "service/server/command_auth.h"

#include <gtest/gtest.h>

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/signature.h>

#include <string>

#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

const std::string kKey = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";
const std::string kChannel = "CONTACTSIM_BODY_CMD";
constexpr uint64_t kNow = 1764633600000000000ULL;  // ns, the test's fixed clock
constexpr uint64_t kMilli = 1000000ULL;            // ns

std::string Payload() {
  body_cmd_t m{};
  m.client_id = "py-test";
  m.request_id = 7;
  m.op = body_cmd_t::REMOVE;
  m.body_id = 3;
  const auto bytes = testing::Encode(m);
  return std::string(bytes.begin(), bytes.end());
}

std::string SignedAt(uint64_t seq, const std::string& key = kKey, const std::string& channel = kChannel) {
  const std::string payload = Payload();
  return payload + SignatureTrailer(key, channel, payload.data(), static_cast<int>(payload.size()), seq);
}

CommandAuthenticator MakeGate(double window_s = 30.0) {
  return CommandAuthenticator(kKey, window_s, [] { return kNow; });
}

Status Admit(const CommandAuthenticator& gate, const std::string& message, int* payload_size = nullptr,
             uint64_t* seq = nullptr) {
  int n = 0;
  uint64_t s = 0;
  return gate.Admit(kChannel, message.data(), static_cast<int>(message.size()), payload_size ? payload_size : &n,
                    seq ? seq : &s);
}

// Verifies that a signed, fresh command passes and that its payload decodes
// as the command that was signed.
TEST(CommandAuthTest, SignedCommandIsAdmitted) {
  const CommandAuthenticator gate = MakeGate();
  const std::string message = SignedAt(kNow - 5 * kMilli);
  int payload_size = 0;
  uint64_t seq = 0;
  const Status st = Admit(gate, message, &payload_size, &seq);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(payload_size, static_cast<int>(Payload().size()));
  EXPECT_EQ(seq, kNow - 5 * kMilli);
  body_cmd_t decoded;
  ASSERT_GE(decoded.decode(message.data(), 0, payload_size), 0);
  EXPECT_EQ(decoded.client_id, "py-test");
  EXPECT_EQ(decoded.body_id, 3);
}

// Verifies that a command without a trailer is refused as unsigned, naming
// the channel and why.
TEST(CommandAuthTest, UnsignedCommandIsRefused) {
  const Status st = Admit(MakeGate(), Payload());
  EXPECT_EQ(st.code(), StatusCode::kUnauthenticated);
  EXPECT_EQ(st.message(),
            "unsigned command on CONTACTSIM_BODY_CMD: commands must be signed (auth_key_file is set)");
}

// Verifies that another key, another channel or an altered byte is forged.
TEST(CommandAuthTest, ForgedCommandsAreRefused) {
  const CommandAuthenticator gate = MakeGate();
  std::string altered = SignedAt(kNow);
  altered[20] = static_cast<char>(altered[20] ^ 0x01);
  for (const std::string& message :
       {SignedAt(kNow, std::string(32, 'x')), SignedAt(kNow, kKey, "CONTACTSIM_SCENE_CMD"), altered}) {
    const Status st = Admit(gate, message);
    EXPECT_EQ(st.code(), StatusCode::kUnauthenticated);
    EXPECT_EQ(st.message().rfind("forged command on CONTACTSIM_BODY_CMD: ", 0), 0u) << st.message();
  }
}

// Verifies that a command signed longer ago (or further ahead) than the
// window is stale, with the age and the window in the message.
TEST(CommandAuthTest, StaleCommandIsRefused) {
  const CommandAuthenticator gate = MakeGate(30.0);
  Status st = Admit(gate, SignedAt(kNow - 95200 * kMilli));
  EXPECT_EQ(st.code(), StatusCode::kUnauthenticated);
  EXPECT_NE(st.message().find("stale command on CONTACTSIM_BODY_CMD: signed 95.2 s ago, window 30 s"),
            std::string::npos)
      << st.message();
  st = Admit(gate, SignedAt(kNow + 40000 * kMilli));
  EXPECT_NE(st.message().find("signed 40.0 s in the future, window 30 s"), std::string::npos) << st.message();
  EXPECT_TRUE(Admit(gate, SignedAt(kNow - 29000 * kMilli)).ok());
}

// Verifies that a seq is accepted once per client, that clients do not
// share windows, and that a reordered seq within 64 still passes.
TEST(CommandAuthTest, ReplayedSequenceIsRefused) {
  CommandAuthenticator gate = MakeGate();
  EXPECT_TRUE(gate.AcceptSequence("py-test", kNow).ok());
  const Status st = gate.AcceptSequence("py-test", kNow);
  EXPECT_EQ(st.code(), StatusCode::kUnauthenticated);
  EXPECT_EQ(st.message(), "replayed: seq " + std::to_string(kNow) + " was seen before (command from \"py-test\")");
  EXPECT_TRUE(gate.AcceptSequence("cpp-42", kNow).ok());
  EXPECT_TRUE(gate.AcceptSequence("py-test", kNow + 10).ok());
  EXPECT_TRUE(gate.AcceptSequence("py-test", kNow + 3).ok());
  EXPECT_FALSE(gate.AcceptSequence("py-test", kNow + 3).ok());
}

// Verifies that the table of clients is bounded: with room for two, the
// least recently seen client is forgotten.
TEST(CommandAuthTest, ClientTableIsBounded) {
  CommandAuthenticator gate(kKey, 30.0, [] { return kNow; }, 2);
  EXPECT_TRUE(gate.AcceptSequence("a", kNow).ok());
  EXPECT_TRUE(gate.AcceptSequence("b", kNow).ok());
  EXPECT_TRUE(gate.AcceptSequence("c", kNow).ok());  // forgets a
  EXPECT_FALSE(gate.AcceptSequence("c", kNow).ok());
  EXPECT_TRUE(gate.AcceptSequence("a", kNow).ok());
}

}  // namespace
}  // namespace contactsim
