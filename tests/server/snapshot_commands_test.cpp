// Tests of SNAPSHOT, RESTORE and REWIND through the server (recording
// transport, no network): a restored or rewound run repeats the original
// bit for bit, for every registered contact method.
#include <gtest/gtest.h>

#include <unistd.h>

#include "service/contact/contact_method_registry.h"
#include "service/scene/snapshot.h"
#include "service/server/snapshot_store.h"
#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

constexpr int kSnapshotStep = 40, kLastStep = 160;

// A ground, a sliding box, a stack of two and commands at several steps
// (a force for a while, an impulse, a velocity change, a material change),
// so that a rewind must replay the journal to get the run right.
// A method without restitution (barrier; method_contract.h) refuses bouncy
// bodies, so they are added with restitution 0 there.
void BuildScene(ServerHarness& h, const std::string& method) {
  const bool elastic = FindContactMethod(method)->contract.restitution;
  auto add = [&](body_cmd_t m) {
    if (!elastic) m.has_restitution = true, m.restitution = 0.0;
    ASSERT_EQ(h.Send(m).code, reply_t::OK);
  };
  body_cmd_t ground = h.Body(body_cmd_t::ADD);
  ground.shape = body_cmd_t::PLANE;
  ground.plane_normal[2] = 1.0;
  ground.fixed = true;
  add(ground);
  add(h.Box(0.1, Vec3(0, 0, 0.1), Vec3(0.5, 0, 0)));
  add(h.Box(0.1, Vec3(0.6, 0, 0.1)));
  add(h.Box(0.1, Vec3(0.6, 0, 0.31)));
}

// Commands that hit the run after the snapshot, at fixed steps.
std::vector<uint64_t> RunWithCommands(ServerHarness& h, int from, int to) {
  std::vector<uint64_t> hashes;
  for (int step = from; step < to; step += 20) {
    body_cmd_t cmd = h.Body(body_cmd_t::APPLY_IMPULSE, 2);
    cmd.impulse[1] = 0.3;
    if (step % 40 == 0) {
      cmd = h.Body(body_cmd_t::APPLY_FORCE, 4);
      cmd.force[0] = -8.0;
      cmd.duration = 0.05;
    }
    EXPECT_EQ(h.Send(cmd).code, reply_t::OK);
    const auto more = h.Step(20);
    hashes.insert(hashes.end(), more.begin(), more.end());
  }
  return hashes;
}

class SnapshotCommandsTest : public ::testing::TestWithParam<std::string> {};

// Verifies: run, snapshot at k, run to n; restore k, run to n again gives
// the same hash at every step; rewinding to a step between k and n (nearest
// snapshot + journal replay) lands on that step's hash and runs on to n
// identically.
TEST_P(SnapshotCommandsTest, RestoreAndRewindRepeatTheRunBitForBit) {
  ServerOptions options;
  options.prefix = "S";
  options.snapshot_every = 30;  // periodic snapshots at 30, 60, ...: REWIND picks the nearest
  ServerHarness h(options, GetParam());
  BuildScene(h, GetParam());
  h.Step(kSnapshotStep);
  scene_cmd_t snap = h.Scene(scene_cmd_t::SNAPSHOT);
  snap.name = "k";
  reply_t r = h.Send(snap);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  const std::vector<uint64_t> original = RunWithCommands(h, kSnapshotStep, kLastStep);
  ASSERT_EQ(original.size(), static_cast<size_t>(kLastStep - kSnapshotStep));

  scene_cmd_t restore = h.Scene(scene_cmd_t::RESTORE);
  restore.name = "k";
  r = h.Send(restore);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(h.server.world().step, kSnapshotStep);
  const std::vector<uint64_t> again = RunWithCommands(h, kSnapshotStep, kLastStep);
  for (size_t i = 0; i < original.size(); ++i) {
    ASSERT_EQ(again[i], original[i]) << "after restore, first divergence at step " << kSnapshotStep + 1 + i;
  }

  for (int target : {kLastStep - 1, 95, kSnapshotStep + 1}) {
    scene_cmd_t rewind = h.Scene(scene_cmd_t::REWIND);
    rewind.target_step = target;
    r = h.Send(rewind);
    ASSERT_EQ(r.code, reply_t::OK) << r.message;
    ASSERT_EQ(h.server.world().step, target);
    EXPECT_EQ(HashWorldState(h.server.world()), original[target - kSnapshotStep - 1]) << "rewind to " << target;
  }
  // the course after the rewind point was forgotten: run on with the same
  // commands from step 41 to 160 and compare again
  const auto tail = h.Step(19);  // 41 -> 60, then the commands as before
  const auto rest = RunWithCommands(h, 60, kLastStep);
  for (size_t i = 0; i < tail.size(); ++i) ASSERT_EQ(tail[i], original[kSnapshotStep + 1 + i - kSnapshotStep]);
  for (size_t i = 0; i < rest.size(); ++i) ASSERT_EQ(rest[i], original[60 + i - kSnapshotStep]) << 61 + i;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, SnapshotCommandsTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// Verifies that bad snapshot commands are refused with a message naming the
// field and leave the world untouched.
TEST(SnapshotCommandsErrorsTest, BadRequestsAreRefused) {
  ServerOptions options;
  options.prefix = "E";
  ServerHarness h(options);
  BuildScene(h, "impulse");
  h.Step(10);
  const uint64_t before = HashWorldState(h.server.world());
  scene_cmd_t cmd = h.Scene(scene_cmd_t::RESTORE);
  cmd.name = "missing";
  reply_t r = h.Send(cmd);
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_NE(r.message.find("no snapshot named \"missing\""), std::string::npos) << r.message;
  cmd.name = "a b";
  r = h.Send(cmd);
  EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
  EXPECT_NE(r.message.find("name must be"), std::string::npos) << r.message;
  cmd.name = "";
  r = h.Send(cmd);
  EXPECT_NE(r.message.find("exactly one of name or path"), std::string::npos) << r.message;
  cmd.path = "/nonexistent/snapshot.pb";
  r = h.Send(cmd);
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  cmd = h.Scene(scene_cmd_t::REWIND);
  cmd.target_step = 11;
  r = h.Send(cmd);
  EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
  EXPECT_NE(r.message.find("step must be in [0, 10]"), std::string::npos) << r.message;
  EXPECT_EQ(HashWorldState(h.server.world()), before);
}

// Verifies that a snapshot saved to a file restores to the same world.
TEST(SnapshotCommandsErrorsTest, FileSnapshotsRestore) {
  ServerOptions options;
  options.prefix = "F";
  ServerHarness h(options, "penalty");
  BuildScene(h, "penalty");
  h.Step(25);
  const uint64_t at25 = HashWorldState(h.server.world());
  const std::string path = "/tmp/contactsim-snapcmd-" + std::to_string(::getpid()) + ".pb";
  scene_cmd_t cmd = h.Scene(scene_cmd_t::SNAPSHOT);
  cmd.path = path;
  ASSERT_EQ(h.Send(cmd).code, reply_t::OK);
  const auto after = h.Step(10);
  cmd = h.Scene(scene_cmd_t::RESTORE);
  cmd.path = path;
  reply_t r = h.Send(cmd);
  ::unlink(path.c_str());
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(HashWorldState(h.server.world()), at25);
  EXPECT_EQ(h.Step(10), after);
}

}  // namespace
}  // namespace contactsim

namespace contactsim {
namespace {

// Verifies that a long run's history is bounded: beyond max_snapshots
// periodic snapshots the oldest one and the journal records before the
// next one are dropped, REWIND reaches back to the oldest snapshot kept and
// no further (with a reply naming the range), and a rewind inside the range
// still lands on the original run's state bit for bit.
TEST(SnapshotHistoryTest, OldHistoryIsDroppedAndRewindStaysExact) {
  ServerOptions options;
  options.prefix = "H";
  options.snapshot_every = 10;
  options.max_snapshots = 2;
  ServerHarness h(options);
  BuildScene(h, "impulse");
  const std::vector<uint64_t> original = RunWithCommands(h, 0, 60);  // a command every 20 steps
  ASSERT_EQ(original.size(), 60u);
  // snapshots at 40, 50 and 60 are kept (the base and two periodic ones)
  scene_cmd_t rewind = h.Scene(scene_cmd_t::REWIND);
  rewind.target_step = 35;
  reply_t r = h.Send(rewind);
  EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
  EXPECT_NE(r.message.find("step must be in [40, 60]"), std::string::npos) << r.message;
  EXPECT_EQ(h.server.world().step, 60);
  EXPECT_EQ(HashWorldState(h.server.world()), original.back());
  for (int target : {45, 40}) {
    rewind.target_step = target;
    r = h.Send(rewind);
    ASSERT_EQ(r.code, reply_t::OK) << r.message;
    EXPECT_EQ(HashWorldState(h.server.world()), original[target - 1]) << "rewind to " << target;
  }
}

// Verifies the store's bookkeeping: records older than the oldest kept
// snapshot are dropped with it, so memory stays bounded on a long run.
TEST(SnapshotHistoryTest, StoreKeepsOnlyRecordsAfterTheOldestSnapshot) {
  SnapshotStore store(2);
  auto snapshot = [](int64_t step, int64_t seq) {
    proto::Snapshot s;
    s.set_step(step);
    s.set_journal_seq(seq);
    return s;
  };
  store.StartTimeline(snapshot(0, 0));
  int64_t seq = 0;
  for (int64_t step = 1; step <= 100; ++step) {
    JournalRecord record;
    record.seq = seq++;
    record.step = step;
    store.AddRecord(record);
    if (step % 10 == 0) store.AddPeriodic(snapshot(step, seq));
    EXPECT_LE(store.snapshot_count(), 3u);
    EXPECT_LE(store.record_count(), 30u) << "at step " << step;
  }
  EXPECT_EQ(store.base_step(), 80);
  SnapshotStore::Plan plan;
  EXPECT_FALSE(store.PlanRewind(79, 100, &plan).ok());
  ASSERT_TRUE(store.PlanRewind(95, 100, &plan).ok());
  EXPECT_EQ(plan.from->step(), 90);
  // the records of boundaries 91..94 (the one of boundary 90 is in the
  // snapshot here; a record of boundary 95 comes after the state at 95)
  ASSERT_EQ(plan.records.size(), 4u);
  EXPECT_EQ(plan.records.front()->step, 91);
}

}  // namespace
}  // namespace contactsim
