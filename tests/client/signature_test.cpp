// Signed messages (protocol/include/contactsim/signature.h): the wire
// format against a pinned vector, every way a message can fail the mac, and
// the anti-replay window.
#include "contactsim/signature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "test_key.h"

namespace contactsim {
namespace {

const std::string kChannel = "CONTACTSIM_BODY_CMD";
const std::string kPayload = "contactsim test payload";
constexpr uint64_t kSeq = 1764633600000000000ULL;  // 2025-12-02T00:00:00Z
constexpr uint64_t kSecond = 1000000000ULL;        // ns
constexpr double kWindow = kDefaultAuthWindowSeconds;

std::string Hex(const std::string& bytes) {
  std::string out;
  char byte[3];
  for (unsigned char c : bytes) {
    std::snprintf(byte, sizeof(byte), "%02x", c);
    out += byte;
  }
  return out;
}

Verified Verify(const std::string& message, const std::string& key = testing::kTestKey, const std::string& channel = kChannel) {
  return VerifySignature(key, channel, message.data(), static_cast<int>(message.size()));
}

std::string SignedAt(uint64_t seq) {
  return kPayload + SignatureTrailer(testing::kTestKey, kChannel, kPayload.data(), static_cast<int>(kPayload.size()), seq);
}

// Verifies the bytes of the protocol's test vector, which the Python client's
// tests pin too (tests/python/test_auth_unit.py), so both sign identically.
TEST(SignatureTest, TrailerMatchesThePinnedTestVector) {
  const std::string trailer =
      SignatureTrailer(testing::kTestKey, kChannel, kPayload.data(), static_cast<int>(kPayload.size()), kSeq);
  EXPECT_EQ(Hex(trailer),
            "43534731"                                                           // "CSG1"
            "0000b8e6e83c7d18"                                                   // seq, little-endian
            "6ebd12a8848bafd0607375328e5c7af72b67ee6d37b007ec580e53a8d1397246");  // HMAC-SHA256
  EXPECT_EQ(static_cast<int>(trailer.size()), kSignatureTrailerBytes);
}

// Verifies that a signed message verifies and yields its payload size and seq.
TEST(SignatureTest, SignedMessageRoundTrips) {
  Signer signer(testing::kTestKey);
  const std::string message = signer.Sign(kChannel, kPayload.data(), static_cast<int>(kPayload.size()));
  ASSERT_EQ(message.size(), kPayload.size() + kSignatureTrailerBytes);
  EXPECT_EQ(message.substr(0, kPayload.size()), kPayload);
  const Verified v = Verify(message);
  ASSERT_TRUE(v.ok) << v.error;
  EXPECT_EQ(v.payload_size, static_cast<int>(kPayload.size()));
  EXPECT_EQ(v.seq, signer.last_seq());
}

// Verifies that an empty payload can be signed and verified.
TEST(SignatureTest, EmptyPayloadRoundTrips) {
  Signer signer(testing::kTestKey);
  const std::string message = signer.Sign(kChannel, "", 0);
  const Verified v = Verify(message);
  ASSERT_TRUE(v.ok) << v.error;
  EXPECT_EQ(v.payload_size, 0);
}

// Verifies that another key's signature is refused as forged.
TEST(SignatureTest, WrongKeyIsForged) {
  const Verified v = Verify(SignedAt(kSeq), std::string(32, 'x'));
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.error.rfind("forged:", 0), 0u) << v.error;
}

// Verifies that a message signed for one channel is refused on another.
TEST(SignatureTest, WrongChannelIsForged) {
  const Verified v = Verify(SignedAt(kSeq), testing::kTestKey, "CONTACTSIM_SCENE_CMD");
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.error.rfind("forged:", 0), 0u) << v.error;
}

// Verifies that the NUL after the channel keeps a byte from moving between
// the channel and the payload.
TEST(SignatureTest, ChannelAndPayloadBoundaryIsSigned) {
  const std::string message = SignedAt(kSeq);
  const std::string moved = message.substr(1);  // "ontactsim ..." on channel "..._CMDc"
  EXPECT_FALSE(Verify(moved, testing::kTestKey, kChannel + "c").ok);
}

// Verifies that flipping any one bit of the payload, the seq or the mac
// makes the message forged (or, in the magic, unsigned).
TEST(SignatureTest, EveryFlippedBitIsRefused) {
  const std::string message = SignedAt(kSeq);
  for (size_t i = 0; i < message.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string bad = message;
      bad[i] = static_cast<char>(bad[i] ^ (1 << bit));
      const Verified v = Verify(bad);
      ASSERT_FALSE(v.ok) << "byte " << i << " bit " << bit;
      const bool in_magic = i >= kPayload.size() && i < kPayload.size() + kSignatureMagicBytes;
      EXPECT_EQ(v.error.rfind(in_magic ? "unsigned:" : "forged:", 0), 0u) << "byte " << i << ": " << v.error;
    }
  }
}

// Verifies that a message without a trailer, or with a cut one, is unsigned.
TEST(SignatureTest, MissingOrTruncatedTrailerIsUnsigned) {
  const Verified plain = Verify(kPayload);
  EXPECT_FALSE(plain.ok);
  EXPECT_EQ(plain.error.rfind("unsigned:", 0), 0u) << plain.error;
  const std::string message = SignedAt(kSeq);
  for (size_t cut = 1; cut <= kSignatureTrailerBytes; ++cut) {
    const Verified v = Verify(message.substr(0, message.size() - cut));
    EXPECT_FALSE(v.ok) << "cut " << cut;
  }
  EXPECT_FALSE(Verify("").ok);
}

// Verifies that a receiver without a key strips a trailer and leaves other
// messages whole.
TEST(SignatureTest, UnsignedSizeStripsOnlyATrailer) {
  const std::string message = SignedAt(kSeq);
  EXPECT_EQ(UnsignedSize(message.data(), static_cast<int>(message.size())), static_cast<int>(kPayload.size()));
  EXPECT_EQ(UnsignedSize(kPayload.data(), static_cast<int>(kPayload.size())), static_cast<int>(kPayload.size()));
  EXPECT_EQ(UnsignedSize("CSG1", 4), 4);
}

// Verifies that seqs increase strictly even when signed faster than the
// clock ticks and from several threads.
TEST(SignatureTest, SignerSeqsIncreaseStrictly) {
  Signer signer(testing::kTestKey);
  std::vector<std::vector<uint64_t>> seqs(4);
  std::vector<std::thread> threads;
  for (auto& out : seqs) {
    threads.emplace_back([&signer, &out] {
      for (int i = 0; i < 500; ++i) out.push_back(Verify(signer.Sign(kChannel, "x", 1)).seq);
    });
  }
  for (std::thread& t : threads) t.join();
  std::vector<uint64_t> all;
  for (const auto& out : seqs) {
    for (size_t i = 1; i < out.size(); ++i) EXPECT_GT(out[i], out[i - 1]);
    all.insert(all.end(), out.begin(), out.end());
  }
  std::sort(all.begin(), all.end());
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end()) << "a seq was used twice";
}

// Verifies that a restarted sender (a new Signer) continues above its old
// seqs, so the receiver's window accepts it.
TEST(SignatureTest, RestartedSignerContinuesAboveTheOldSeq) {
  ReplayWindow window;
  std::string why;
  uint64_t old_last = 0;
  {
    Signer before(testing::kTestKey);
    for (int i = 0; i < 100; ++i) before.Sign(kChannel, "x", 1);
    old_last = before.last_seq();
    ASSERT_TRUE(window.Accept("client", old_last, WallClockNanoseconds(), kWindow, &why)) << why;
  }
  Signer after(testing::kTestKey);
  const Verified v = Verify(after.Sign(kChannel, "x", 1));
  EXPECT_GT(v.seq, old_last);
  EXPECT_TRUE(window.Accept("client", v.seq, WallClockNanoseconds(), kWindow, &why)) << why;
}

// Verifies that seqs outside the window around now are stale, in the past
// and in the future, with the age in the reason.
TEST(ReplayWindowTest, StaleSeqsAreRefused) {
  ReplayWindow window;
  std::string why;
  const uint64_t now = kSeq + 95200 * (kSecond / 1000);  // 95.2 s after kSeq
  EXPECT_FALSE(window.Accept("a", kSeq, now, 30.0, &why));
  EXPECT_EQ(why, "stale: signed 95.2 s ago, window 30 s");
  EXPECT_FALSE(window.Accept("a", now + 31 * kSecond, now, 30.0, &why));
  EXPECT_EQ(why, "stale: signed 31.0 s in the future, window 30 s");
  EXPECT_TRUE(window.Accept("a", now - 29 * kSecond, now, 30.0, &why)) << why;
  EXPECT_TRUE(window.Accept("a", now + 29 * kSecond, now, 30.0, &why)) << why;
}

// Verifies that the same seq from the same sender is accepted once, and
// that senders do not share windows.
TEST(ReplayWindowTest, ReplayedSeqIsRefused) {
  ReplayWindow window;
  std::string why;
  EXPECT_TRUE(window.Accept("a", kSeq, kSeq, kWindow, &why));
  EXPECT_FALSE(window.Accept("a", kSeq, kSeq, kWindow, &why));
  EXPECT_EQ(why.rfind("replayed:", 0), 0u) << why;
  EXPECT_TRUE(window.Accept("b", kSeq, kSeq, kWindow, &why)) << why;
}

// Verifies that up to 64 seqs below the newest are accepted once each in
// any order, and older ones are refused.
TEST(ReplayWindowTest, ReorderedWithin64AreAcceptedOnce) {
  ReplayWindow window;
  std::string why;
  const uint64_t top = kSeq + 1000;
  ASSERT_TRUE(window.Accept("a", top, kSeq, kWindow, &why));
  for (uint64_t below = kReplayWindowSlots - 1; below >= 1; --below) {
    EXPECT_TRUE(window.Accept("a", top - below, kSeq, kWindow, &why)) << below << ": " << why;
    EXPECT_FALSE(window.Accept("a", top - below, kSeq, kWindow, &why)) << below;
  }
  EXPECT_FALSE(window.Accept("a", top - kReplayWindowSlots, kSeq, kWindow, &why));
  EXPECT_NE(why.find("more than 64 below"), std::string::npos) << why;
}

// Verifies that moving the newest seq up keeps what was seen within reach
// and forgets what fell out of the window.
TEST(ReplayWindowTest, WindowSlidesWithTheNewestSeq) {
  ReplayWindow window;
  std::string why;
  ASSERT_TRUE(window.Accept("a", kSeq, kSeq, kWindow, &why));
  ASSERT_TRUE(window.Accept("a", kSeq + 10, kSeq, kWindow, &why));
  EXPECT_FALSE(window.Accept("a", kSeq, kSeq, kWindow, &why)) << "still within 64: remembered";
  EXPECT_TRUE(window.Accept("a", kSeq + 5, kSeq, kWindow, &why)) << why;
  ASSERT_TRUE(window.Accept("a", kSeq + 200, kSeq, kWindow, &why));  // jump past the window
  EXPECT_FALSE(window.Accept("a", kSeq + 10, kSeq, kWindow, &why));
  EXPECT_TRUE(window.Accept("a", kSeq + 199, kSeq, kWindow, &why)) << why;
}

// Verifies that the table holds at most max_senders, forgetting the least
// recently seen sender first.
TEST(ReplayWindowTest, SenderTableIsBoundedByRecency) {
  ReplayWindow window(3);
  std::string why;
  for (const char* sender : {"a", "b", "c"}) ASSERT_TRUE(window.Accept(sender, kSeq, kSeq, kWindow, &why));
  ASSERT_TRUE(window.Accept("a", kSeq + 1, kSeq, kWindow, &why));  // a is now the most recent
  ASSERT_TRUE(window.Accept("d", kSeq, kSeq, kWindow, &why));      // evicts b
  EXPECT_EQ(window.size(), 3u);
  EXPECT_FALSE(window.Accept("a", kSeq + 1, kSeq, kWindow, &why)) << "a was kept";
  EXPECT_FALSE(window.Accept("c", kSeq, kSeq, kWindow, &why)) << "c was kept";
  EXPECT_TRUE(window.Accept("b", kSeq, kSeq, kWindow, &why)) << "b was forgotten: " << why;
  EXPECT_EQ(window.size(), 3u);
}

// Verifies the default bound of 4,096 senders.
TEST(ReplayWindowTest, DefaultTableHolds4096Senders) {
  ReplayWindow window;
  std::string why;
  for (int i = 0; i < 5000; ++i) ASSERT_TRUE(window.Accept(std::to_string(i), kSeq, kSeq, kWindow, &why));
  EXPECT_EQ(window.size(), kDefaultMaxReplaySenders);
}

class AuthKeyFileTest : public ::testing::Test {
 protected:
  std::string Write(const std::string& content) {
    path_ = ::testing::TempDir() + "contactsim-auth-key-test";
    std::ofstream(path_, std::ios::binary) << content;
    return path_;
  }
  void TearDown() override {
    if (!path_.empty()) std::remove(path_.c_str());
  }
  std::string path_;
};

// Verifies that a key file's trailing whitespace is not part of the key.
TEST_F(AuthKeyFileTest, TrailingWhitespaceIsStripped) {
  std::string key, error;
  ASSERT_TRUE(LoadAuthKey(Write(testing::kTestKey + " \r\n\n"), &key, &error)) << error;
  EXPECT_EQ(key, testing::kTestKey);
}

// Verifies that a short key is refused with the file's name and a hint.
TEST_F(AuthKeyFileTest, ShortKeyIsRefused) {
  std::string key, error;
  const std::string path = Write(std::string(31, 'k') + "\n");
  EXPECT_FALSE(LoadAuthKey(path, &key, &error));
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("31 bytes"), std::string::npos) << error;
  EXPECT_NE(error.find("openssl rand -hex 32"), std::string::npos) << error;
}

// Verifies that a missing key file is refused with its name and the reason.
TEST_F(AuthKeyFileTest, MissingFileIsRefused) {
  std::string key, error;
  EXPECT_FALSE(LoadAuthKey("/nonexistent/contactsim.key", &key, &error));
  EXPECT_NE(error.find("\"/nonexistent/contactsim.key\""), std::string::npos) << error;
  EXPECT_NE(error.find("No such file"), std::string::npos) << error;
}

// Verifies that an explicit path wins over the environment variable.
TEST(AuthKeyFileEnvTest, ExplicitPathWinsOverTheEnvironment) {
  ::setenv(kAuthKeyFileEnv, "/from/env", 1);
  EXPECT_EQ(ResolveAuthKeyFile(""), "/from/env");
  EXPECT_EQ(ResolveAuthKeyFile("/given"), "/given");
  ::unsetenv(kAuthKeyFileEnv);
  EXPECT_EQ(ResolveAuthKeyFile(""), "");
}

}  // namespace
}  // namespace contactsim
