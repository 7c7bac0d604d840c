// Tests of the command journal: record framing, torn tails, snapshots and
// segments on disk, and recovery of a server from its journal folder.
#include "service/server/journal.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "service/scene/snapshot.h"
#include "tests/server/server_harness.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

namespace fs = std::filesystem;
using testing::ServerHarness;
using testing::TempDir;

// Verifies that records survive encoding, and that any damage (a flipped
// byte, a cut) is detected rather than read as a different command.
TEST(JournalTest, RecordsRoundTripAndDamageIsDetected) {
  JournalRecord a{7, 120, RecordKind::kBodyCommand, std::string("\x01\x02payload\x00z", 11)};
  JournalRecord b{8, 121, RecordKind::kStepTo, ""};
  std::string bytes;
  EncodeRecord(a, &bytes);
  EncodeRecord(b, &bytes);
  size_t offset = 0;
  JournalRecord r;
  ASSERT_TRUE(DecodeRecord(bytes, &offset, &r));
  EXPECT_EQ(r.seq, 7);
  EXPECT_EQ(r.step, 120);
  EXPECT_EQ(r.kind, RecordKind::kBodyCommand);
  EXPECT_EQ(r.payload, a.payload);
  ASSERT_TRUE(DecodeRecord(bytes, &offset, &r));
  EXPECT_EQ(r.kind, RecordKind::kStepTo);
  EXPECT_EQ(offset, bytes.size());

  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string damaged = bytes;
    damaged[i] ^= 0x10;
    size_t at = 0;
    JournalRecord first;
    const bool ok = DecodeRecord(damaged, &at, &first);
    if (ok) {
      EXPECT_TRUE(first.seq == 7 && first.payload == a.payload && i >= at) << "byte " << i;
    }
  }
  for (size_t cut = 0; cut < bytes.size(); ++cut) {
    size_t at = 0;
    JournalRecord x;
    const std::string part = bytes.substr(0, cut);
    int n = 0;
    while (DecodeRecord(part, &at, &x)) ++n;
    EXPECT_LT(n, 2) << "cut at " << cut;
  }
}

// Verifies that reopening a folder gives back the snapshot and the records
// after it, and that a torn last record is cut off (and appends continue).
TEST(JournalTest, ReopenRecoversSnapshotAndRecordsAndCutsATornTail) {
  TempDir dir;
  {
    Journal j;
    ASSERT_TRUE(j.Open(dir.path(), FsyncPolicy::kAlways).ok());
    EXPECT_FALSE(j.recovered_snapshot());
    ASSERT_TRUE(j.Append(RecordKind::kBodyCommand, 0, "old").ok());
    proto::Snapshot s;
    s.set_step(5);
    ASSERT_TRUE(j.WriteSnapshot(s).ok());
    ASSERT_TRUE(j.Append(RecordKind::kSceneCommand, 5, "a").ok());
    ASSERT_TRUE(j.Append(RecordKind::kBodyCommand, 9, "b").ok());
    ASSERT_TRUE(j.Sync().ok());
  }
  // tear the last record: the crash came in the middle of a write
  std::string segment;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    if (e.path().filename().string().rfind("journal-", 0) == 0) segment = e.path().string();
  }
  ASSERT_FALSE(segment.empty());
  fs::resize_file(segment, fs::file_size(segment) - 3);
  Journal j;
  ASSERT_TRUE(j.Open(dir.path(), FsyncPolicy::kNone).ok());
  ASSERT_TRUE(j.recovered_snapshot());
  EXPECT_EQ(j.recovered_snapshot()->step(), 5);
  EXPECT_EQ(j.recovered_snapshot()->journal_seq(), 1);
  ASSERT_EQ(j.recovered_records().size(), 1u);
  EXPECT_EQ(j.recovered_records()[0].payload, "a");
  EXPECT_EQ(j.next_seq(), 2);
  ASSERT_TRUE(j.Append(RecordKind::kBodyCommand, 10, "c").ok());
  ASSERT_TRUE(j.Sync().ok());
  Journal again;
  ASSERT_TRUE(again.Open(dir.path(), FsyncPolicy::kNone).ok());
  ASSERT_EQ(again.recovered_records().size(), 2u);
  EXPECT_EQ(again.recovered_records()[1].payload, "c");
  EXPECT_EQ(again.recovered_records()[1].seq, 2);
}

// Verifies that a payload longer than recovery reads back
// (kMaxJournalPayload) is refused at Append, not written to be cut off with
// every record after it on the next open, and that appends go on.
TEST(JournalTest, AppendRefusesARecordRecoveryCouldNotRead) {
  TempDir dir;
  {
    Journal j;
    ASSERT_TRUE(j.Open(dir.path(), FsyncPolicy::kNone).ok());
    ASSERT_TRUE(j.Append(RecordKind::kBodyCommand, 1, "before").ok());
    const Status st = j.Append(RecordKind::kBodyCommand, 2, std::string(kMaxJournalPayload + 1, 'y'));
    EXPECT_EQ(st.code(), StatusCode::kResourceExhausted) << st.message();
    EXPECT_NE(st.message().find(std::to_string(kMaxJournalPayload + 1)), std::string::npos) << st.message();
    ASSERT_TRUE(j.Append(RecordKind::kBodyCommand, 3, "after").ok());
    ASSERT_TRUE(j.Sync().ok());
  }
  Journal again;
  ASSERT_TRUE(again.Open(dir.path(), FsyncPolicy::kNone).ok());
  ASSERT_EQ(again.recovered_records().size(), 2u);
  EXPECT_EQ(again.recovered_records()[0].payload, "before");
  EXPECT_EQ(again.recovered_records()[1].payload, "after");
}

// The same commands for every server below: a periodic snapshot lands at
// step 50, then gravity, a force, steps and a new body come after it.
void Drive(ServerHarness& h) {
  body_cmd_t ground = h.Body(body_cmd_t::ADD);
  ground.shape = body_cmd_t::PLANE;
  ground.plane_normal[2] = 1.0;
  ASSERT_EQ(h.Send(ground).code, reply_t::OK);
  ASSERT_EQ(h.Send(h.Box(0.1, Vec3(0, 0, 0.1), Vec3(0.5, 0, 0))).code, reply_t::OK);
  h.Step(70);
  scene_cmd_t g = h.Scene(scene_cmd_t::SET_GRAVITY);
  g.gravity[2] = -5.0;
  ASSERT_EQ(h.Send(g).code, reply_t::OK);
  body_cmd_t push = h.Body(body_cmd_t::APPLY_FORCE, 2);
  push.force[1] = 3.0;
  push.duration = 0.1;  // still acting at step 75
  ASSERT_EQ(h.Send(push).code, reply_t::OK);
  h.Step(5);
  ASSERT_EQ(h.Send(h.Box(0.05, Vec3(1, 1, 0.3))).code, reply_t::OK);
}

// Verifies that a server restarted on its journal folder comes back with
// the world it had (snapshot at step 50 + the journal after it), bit for
// bit, and continues as a server that never stopped.
TEST(JournalTest, ServerRecoversTheSameWorldFromItsFolder) {
  TempDir dir;
  ServerOptions options;
  options.prefix = "J";
  options.snapshot_every = 50;
  ServerHarness reference(options, "penalty");
  Drive(reference);
  options.journal_dir = dir.path();
  {
    ServerHarness first(options, "penalty");
    Drive(first);
    ASSERT_EQ(HashWorldState(first.server.world()), HashWorldState(reference.server.world()));
  }
  ServerHarness recovered(options, "impulse");  // the folder's method wins
  EXPECT_STREQ(recovered.server.method().Name(), "penalty");
  EXPECT_EQ(recovered.server.world().step, 75);
  EXPECT_EQ(recovered.server.world().bodies().size(), 3u);
  EXPECT_EQ(HashWorldState(recovered.server.world()), HashWorldState(reference.server.world()));
  EXPECT_EQ(recovered.Step(40), reference.Step(40));
}

}  // namespace
}  // namespace contactsim
