// The command journal: every accepted command that changes the world is
// appended, with the step index at which it applied, before it is
// acknowledged; replaying a snapshot plus the records after it reproduces
// every later step bit for bit (docs/architecture.md, determinism).
//
// On disk (a folder): snapshot-<S>.pb, the latest durable snapshot, whose
// journal_seq is S, and journal-<S>.bin segments holding records S, S+1, ...
// Each record is
//   u32 payload length | u8 kind | i64 seq | i64 step | payload | u32 crc32
// (little-endian; crc32 over kind .. payload), the payload being the LCM
// encoding of the command message. A record torn by a crash fails its
// length or crc check and is cut off, with everything after it, on open.
// Writing a snapshot starts a new segment and deletes the older snapshot and
// segments, so the folder holds one snapshot and the records after it.
//
// Fsync policy: kAlways (the default) makes the records durable before the
// server acknowledges them (one fdatasync per batch of commands, a group
// commit); kNone leaves them to the kernel, which survives a killed server
// but not a power loss.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "service/physics/status.h"
#include "service/proto/snapshot.pb.h"

namespace contactsim {

// The largest payload of one record: recovery takes a longer length field
// for damage, so Append refuses what recovery could not read back.
constexpr uint32_t kMaxJournalPayload = 64u << 20;  // bytes

enum class RecordKind : uint8_t {
  kBodyCommand = 1,   // body_cmd_t
  kSceneCommand = 2,  // scene_cmd_t (gravity, dt, contact method)
  kInput = 3,         // input_t: a lockstep controller's forces for one step
  kStepTo = 4,        // no payload: the world reached `step` (a STEP finished)
  kJointCommand = 5,  // joint_cmd_t
  kSensorCommand = 6, // sensor_cmd_t
  kNotJournaled = 7,  // a query (ray_cast_t): never written
  kModelCommand = 8,  // model_cmd_t, a LOAD always in its resolved form (the model as read)
  kActuatorCommand = 9,  // actuator_cmd_t
  kArmCommand = 10,   // the arm driver's command (lcmt_iiwa_command or lcmt_panda_command, arm_driver/)
  kWsgCommand = 11,   // the WSG driver's command (lcmt_schunk_wsg_command, arm_driver/)
};

struct JournalRecord {
  int64_t seq = 0;   // ascending, never reused
  int64_t step = 0;  // the world's step count when it applied (before step + 1)
  RecordKind kind = RecordKind::kStepTo;
  std::string payload;
};

enum class FsyncPolicy { kAlways, kNone };

// Parses "always" / "none".
Status ParseFsyncPolicy(const std::string& text, FsyncPolicy* policy);

class Journal {
 public:
  Journal() = default;
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Opens (creating it) the folder and reads what a previous run left: the
  // latest snapshot and the records after it (a torn tail is cut off).
  Status Open(const std::string& dir, FsyncPolicy policy);
  bool open() const { return fd_ >= 0; }
  // A rollback that could not cut the segment back leaves the journal
  // unusable: it refuses records until the server restarts.
  bool failed() const { return failed_; }
  const std::string& dir() const { return dir_; }
  // What Open found; empty when the folder was new.
  const std::optional<proto::Snapshot>& recovered_snapshot() const { return recovered_snapshot_; }
  const std::vector<JournalRecord>& recovered_records() const { return recovered_records_; }
  void DropRecovered();

  // The sequence number the next record gets.
  int64_t next_seq() const { return next_seq_; }
  // Assigns the next seq; writes the record when the journal is open (an
  // INTERNAL status when the disk refuses it: nothing of it stays).
  Status Append(RecordKind kind, int64_t step, const std::string& payload, JournalRecord* out = nullptr);
  // Makes every appended record durable (per the policy).
  Status Sync();
  bool dirty() const { return dirty_; }

  // Where the journal stands, and a way back there: the records appended
  // since the mark are cut off, as if never written (a batch whose sync
  // failed is undone this way).
  struct Mark {
    int64_t seq = 0;
    int64_t segment_start = 0;
    int64_t bytes = 0;
  };
  Mark mark() const { return {next_seq_, segment_start_, segment_bytes_}; }
  Status RollBack(const Mark& mark);

  // Writes `snapshot` (its journal_seq set to next_seq()) durably and starts
  // a new segment; older snapshots and segments are deleted.
  Status WriteSnapshot(proto::Snapshot snapshot);

 private:
  Status OpenSegment();
  void Close();

  std::string dir_;
  FsyncPolicy policy_ = FsyncPolicy::kAlways;
  int fd_ = -1;                // the open segment, O_APPEND
  int64_t segment_start_ = 0;
  int64_t segment_bytes_ = 0;  // its length
  bool failed_ = false;
  int64_t next_seq_ = 0;
  bool dirty_ = false;
  std::optional<proto::Snapshot> recovered_snapshot_;
  std::vector<JournalRecord> recovered_records_;
};

// Record framing, exposed for tests and tools: appends one encoded record;
// DecodeRecord reads one at `*offset` and advances it, false on a torn or
// corrupt record.
void EncodeRecord(const JournalRecord& record, std::string* out);
bool DecodeRecord(const std::string& bytes, size_t* offset, JournalRecord* record);

}  // namespace contactsim
