// Tests of the command channel table: every decoder is total (no input
// throws, over-allocates or is half-read) and answers bad bytes with
// DECODE_ERROR and limits with RESOURCE_EXHAUSTED.
#include "service/server/command_channels.h"

#include <contactsim/protocol.hpp>
#include <gtest/gtest.h>

#include <random>
#include <map>
#include <set>

#include "tests/server/command_messages.h"

namespace contactsim {
namespace {

using testing::SampleCommandMessages;
using testing::SampleMessage;

Status DecodeOn(const std::string& suffix, const std::string& bytes, Command* cmd = nullptr,
                const DecodeContext& context = DecodeContext{}) {
  Command scratch;
  return ChannelOfSuffix(suffix)->decode(bytes.data(), static_cast<int>(bytes.size()), context,
                                         cmd != nullptr ? cmd : &scratch);
}

std::string Hex(const std::string& hex) {
  std::string out;
  for (size_t i = 0; i + 1 < hex.size(); i += 2) out.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return out;
}

// Verifies that the table names every channel once, by suffix and by the
// journal's record kind.
TEST(CommandChannelsTest, EveryChannelIsFoundBySuffixAndRecordKind) {
  std::set<std::string> suffixes;
  for (const CommandChannel& c : CommandChannels()) {
    EXPECT_TRUE(suffixes.insert(c.suffix).second) << c.suffix;
    EXPECT_EQ(ChannelOfSuffix(c.suffix), &c);
    EXPECT_EQ(ChannelOfRecord(c.record), &c);
  }
  EXPECT_EQ(suffixes,
            (std::set<std::string>{"BODY_CMD", "SCENE_CMD", "JOINT_CMD", "INPUT", "SENSOR_CMD", "RAY_CAST", "MODEL_CMD",
                                   "ACTUATOR_CMD"}));
  EXPECT_EQ(ChannelOfRecord(RecordKind::kStepTo), nullptr);
  EXPECT_EQ(ChannelOfSuffix("STATE"), nullptr);
}

// Verifies that the table has one row for each incoming channel of the
// protocol (lcmtypes/protocol.toml), in its order, with its type and
// answering, and none for an outgoing one.
TEST(CommandChannelsTest, EveryIncomingChannelOfTheProtocolHasADecoder) {
  std::vector<std::string> incoming;
  for (const protocol::ChannelSpec& spec : protocol::kChannels) {
    if (!spec.incoming) {
      EXPECT_EQ(ChannelOfSuffix(spec.name), nullptr) << spec.name;
      continue;
    }
    incoming.push_back(spec.name);
    const CommandChannel* c = ChannelOfSuffix(spec.name);
    ASSERT_NE(c, nullptr) << spec.name;
    EXPECT_STREQ(c->type_name, spec.type_name);
    EXPECT_EQ(c->replied, spec.replied) << spec.name;
  }
  std::vector<std::string> rows;
  for (const CommandChannel& c : CommandChannels()) rows.push_back(c.suffix);
  EXPECT_EQ(rows, incoming);
}

// Verifies that the payload that once ended the server (a string whose
// length field is 0 made the generated decoder assign 2^64-1 characters)
// is a DECODE_ERROR.
TEST(CommandChannelsTest, ThePayloadThatKilledTheServerIsADecodeError) {
  const std::string bytes = Hex(
      "9efc6968c317985c8000000566757a7a000000007f800000807f00007f7f000000ffff000000007f007f8000007f7f008000ff00800000"
      "0000000000000000007f007f0000000000007f00000000ff008000008000000000010000ff00ff0000000000ff7f000000ff0000");
  for (const CommandChannel& c : CommandChannels()) {
    const Status st = DecodeOn(c.suffix, bytes);
    EXPECT_EQ(st.code(), StatusCode::kDecodeError) << c.suffix << ": " << st.message();
  }
}

// Verifies that a good message of every op decodes (it may still fail its
// own checks, e.g. a scene file that does not exist, but not as bytes) and
// carries its sender.
TEST(CommandChannelsTest, AGoodMessageOfEveryOpDecodes) {
  for (const SampleMessage& m : SampleCommandMessages()) {
    Command cmd;
    const Status st = DecodeOn(m.suffix, m.bytes, &cmd);
    EXPECT_NE(st.code(), StatusCode::kDecodeError) << m.label << ": " << st.message();
    EXPECT_EQ(cmd.client_id, "sample") << m.label;
  }
}

// Verifies that every truncation of every op is a DECODE_ERROR, and so are
// bytes left after the message.
TEST(CommandChannelsTest, EveryTruncationAndTrailingByteIsADecodeError) {
  for (const SampleMessage& m : SampleCommandMessages()) {
    for (size_t n = 0; n < m.bytes.size(); ++n) {
      const Status st = DecodeOn(m.suffix, m.bytes.substr(0, n));
      ASSERT_EQ(st.code(), StatusCode::kDecodeError) << m.label << " cut to " << n << " bytes";
    }
    const Status st = DecodeOn(m.suffix, m.bytes + "x");
    EXPECT_EQ(st.code(), StatusCode::kDecodeError) << m.label;
    EXPECT_NE(st.message().find("1 bytes after the end"), std::string::npos) << st.message();
  }
}

// Writes a big-endian int32 at `at`.
void PutInt32(std::string* bytes, size_t at, int32_t v) {
  for (int i = 0; i < 4; ++i) (*bytes)[at + i] = static_cast<char>((static_cast<uint32_t>(v) >> (24 - 8 * i)) & 0xff);
}

// Verifies that string lengths and array counts that do not fit the bytes
// (0, negative, huge) are refused before anything is allocated from them.
TEST(CommandChannelsTest, LengthsAndCountsThatDoNotFitAreDecodeErrors) {
  for (const SampleMessage& m : SampleCommandMessages()) {
    // every command starts with the fingerprint, then client_id's length
    for (int32_t len : {0, -1, -2147483647 - 1, 2147483647, 1 << 20}) {
      std::string bytes = m.bytes;
      PutInt32(&bytes, 8, len);
      const Status st = DecodeOn(m.suffix, bytes);
      EXPECT_EQ(st.code(), StatusCode::kDecodeError) << m.label << " len " << len;
      EXPECT_NE(st.message().find("client_id"), std::string::npos) << st.message();
    }
  }
  // the input's num_bodies sits after client_id, request_id and step
  const SampleMessage input = SampleCommandMessages().back();
  ASSERT_EQ(input.suffix, "INPUT");
  const size_t count_at = 8 + 4 + std::string("sample").size() + 1 + 8 + 8;
  for (int32_t count : {-1, 3, 1 << 28, 2147483647}) {
    std::string bytes = input.bytes;
    PutInt32(&bytes, count_at, count);
    const Status st = DecodeOn("INPUT", bytes);
    EXPECT_EQ(st.code(), StatusCode::kDecodeError) << count;
    // the first array that no longer fits is named
    EXPECT_NE(st.message().find(count == 3 ? "torques" : "body_ids"), std::string::npos) << st.message();
  }
}

// Verifies that random bit flips and random bytes, on every channel, never
// escape the decoder: each gives a status, and a message that still
// decodes as bytes names its sender.
TEST(CommandChannelsTest, RandomDamageAlwaysGivesAStatus) {
  std::mt19937 rng(20261201);
  const auto samples = SampleCommandMessages();
  int decoded = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const SampleMessage& m = samples[rng() % samples.size()];
    std::string bytes = m.bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] ^= static_cast<char>(1u << (rng() % 8));
    if (trial % 10 == 0) bytes.resize(rng() % (bytes.size() + 64), static_cast<char>(rng()));
    for (const CommandChannel& c : CommandChannels()) {
      const Status st = DecodeOn(c.suffix, bytes);
      decoded += st.code() != StatusCode::kDecodeError;
    }
  }
  EXPECT_GT(decoded, 0);  // flips in number fields leave decodable messages
}

// Verifies that a payload over its channel's limit is refused unread, and a
// convex body over the point limit by name.
TEST(CommandChannelsTest, LimitsAreResourceExhaustedAndNamed) {
  DecodeContext context;
  context.limits.max_scene_cmd_bytes = 100;
  context.limits.max_convex_points = 3;
  for (const SampleMessage& m : SampleCommandMessages()) {
    if (m.suffix == "SCENE_CMD" && m.bytes.size() > 100) {
      const Status st = DecodeOn(m.suffix, m.bytes, nullptr, context);
      EXPECT_EQ(st.code(), StatusCode::kResourceExhausted) << m.label;
      EXPECT_NE(st.message().find("limit of 100 bytes"), std::string::npos) << st.message();
    }
    if (m.label == "BODY_CMD ADD convex") {
      const Status st = DecodeOn(m.suffix, m.bytes, nullptr, context);
      EXPECT_EQ(st.code(), StatusCode::kResourceExhausted);
      EXPECT_NE(st.message().find("max_convex_points = 3"), std::string::npos) << st.message();
    }
  }
}

// Verifies that the admission hook sees the sender before the command's
// own checks and that its refusal is the answer.
TEST(CommandChannelsTest, TheAdmissionHookAnswersFirst) {
  DecodeContext context;
  std::vector<std::string> seen;
  context.admit = [&](const std::string& client) {
    seen.push_back(client);
    return Status::ResourceExhausted("too fast");
  };
  for (const SampleMessage& m : SampleCommandMessages()) {
    Command cmd;
    const Status st = DecodeOn(m.suffix, m.bytes, &cmd, context);
    EXPECT_EQ(st.code(), StatusCode::kResourceExhausted) << m.label;
    const std::map<std::string, int64_t> ids = {{"BODY_CMD", 7},    {"SCENE_CMD", 8},   {"JOINT_CMD", 9},
                                                 {"INPUT", 10},      {"SENSOR_CMD", 11}, {"RAY_CAST", 12}};
    EXPECT_EQ(cmd.request_id, ids.at(m.suffix)) << m.label;
  }
  EXPECT_EQ(seen.size(), SampleCommandMessages().size());
}

}  // namespace
}  // namespace contactsim
