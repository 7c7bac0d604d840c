// Tests that a journal the disk refuses makes honest replies: the commands
// it could not record answer INTERNAL and are not applied, the ones before
// them stay, and a restart recovers exactly what was acknowledged. The
// disk is made to refuse by a file size limit (RLIMIT_FSIZE: writes past it
// fail with EFBIG), which needs neither root nor a special file system.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>

#include "tests/server/server_harness.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ServerHarness;
using testing::TempDir;

// Caps the size of files this process writes at the current size of the
// journal's newest segment plus `extra` bytes, for the scope's life.
class FileSizeCap {
 public:
  FileSizeCap(const std::string& dir, int64_t extra) {
    int64_t largest = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().filename().string().rfind("journal-", 0) == 0) {
        largest = std::max<int64_t>(largest, static_cast<int64_t>(e.file_size()));
      }
    }
    old_handler_ = ::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
    ::getrlimit(RLIMIT_FSIZE, &old_);
    rlimit cap = old_;
    cap.rlim_cur = static_cast<rlim_t>(largest + extra);
    ::setrlimit(RLIMIT_FSIZE, &cap);
  }
  ~FileSizeCap() {
    ::setrlimit(RLIMIT_FSIZE, &old_);
    ::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_{};
  sighandler_t old_handler_;
};

ServerOptions JournalOptions(const std::string& dir) {
  ServerOptions o;
  o.prefix = "J";
  o.journal_dir = dir;
  return o;
}

// Verifies that a command whose record cannot be written answers INTERNAL,
// changes nothing, and that the journal works again once the disk does.
TEST(JournalFailureTest, ARefusedRecordAnswersInternalAndChangesNothing) {
  TempDir dir;
  ServerHarness h(JournalOptions(dir.path()));
  ASSERT_EQ(h.Send(h.Box(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
  const uint64_t before = HashWorldState(h.server.world());
  {
    FileSizeCap cap(dir.path(), 0);
    const reply_t add = h.Send(h.Box(0.1, Vec3(1, 0, 1)));
    EXPECT_EQ(add.code, reply_t::INTERNAL);
    EXPECT_NE(add.message.find("not applied: cannot append to the journal"), std::string::npos) << add.message;
    EXPECT_EQ(add.num_ids, 0);
    scene_cmd_t gravity = h.Scene(scene_cmd_t::SET_GRAVITY);
    gravity.gravity[2] = -1.0;
    EXPECT_EQ(h.Send(gravity).code, reply_t::INTERNAL);
    EXPECT_EQ(h.server.world().bodies().size(), 1u);
    EXPECT_EQ(h.server.world().gravity.z(), -9.81);
    EXPECT_EQ(HashWorldState(h.server.world()), before);
  }
  const reply_t again = h.Send(h.Box(0.1, Vec3(2, 0, 1)));
  EXPECT_EQ(again.code, reply_t::OK) << again.message;
  EXPECT_EQ(h.server.world().bodies().size(), 2u);
}

// Verifies that when a later command of a batch cannot be recorded, the
// whole batch's journaled commands are undone and answered INTERNAL (their
// replies were held for the batch's sync), and a restart recovers the
// world that was acknowledged before the batch.
TEST(JournalFailureTest, ARefusedBatchIsUndoneWholeAndRecoveryAgrees) {
  TempDir dir;
  uint64_t acknowledged = 0;
  {
    ServerHarness h(JournalOptions(dir.path()));
    ASSERT_EQ(h.Send(h.Box(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
    h.Step(3);
    acknowledged = HashWorldState(h.server.world());
    body_cmd_t first = h.Box(0.1, Vec3(1, 0, 1));
    body_cmd_t second = h.Box(0.1, Vec3(2, 0, 1));
    h.Post(first);
    h.Post(second);
    // room for the first record only (header, payload, crc)
    FileSizeCap cap(dir.path(), 4 + 1 + 8 + 8 + first.getEncodedSize() + 4);
    h.server.Tick();
    const auto replies = h.transport.All<reply_t>(h.server.Channel("REPLY"));
    ASSERT_GE(replies.size(), 2u);
    for (size_t i = replies.size() - 2; i < replies.size(); ++i) {
      EXPECT_EQ(replies[i].code, reply_t::INTERNAL) << replies[i].message;
    }
    EXPECT_EQ(h.server.world().bodies().size(), 1u);
    EXPECT_EQ(HashWorldState(h.server.world()), acknowledged);
  }
  ServerHarness recovered(JournalOptions(dir.path()));
  EXPECT_EQ(recovered.server.world().bodies().size(), 1u);
  EXPECT_EQ(recovered.server.world().step, 3);
  EXPECT_EQ(HashWorldState(recovered.server.world()), acknowledged);
}

}  // namespace
}  // namespace contactsim
