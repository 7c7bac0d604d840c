// The server's in-memory history, for SAVE / RESTORE / REWIND: named
// snapshot slots, and the current timeline — a base snapshot, periodic
// snapshots and every journal record since the base. The base is the
// timeline's start until more than max_periodic periodic snapshots were
// taken; then the oldest snapshot and its records are dropped, so the
// history of a long run stays bounded.
//
// A timeline starts whenever the world is replaced rather than changed by
// a journaled command (start, reset, scene load, restore); REWIND reaches
// any step of the current timeline from its nearest snapshot by replaying
// the records after it (docs/snapshots.md).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "service/physics/status.h"
#include "service/proto/snapshot.pb.h"
#include "service/server/journal.h"

namespace contactsim {

class SnapshotStore {
 public:
  explicit SnapshotStore(int max_periodic = 32) : max_periodic_(max_periodic) {}

  // named slots ("" is not a name)
  void Put(const std::string& name, proto::Snapshot snapshot) { slots_[name] = std::move(snapshot); }
  const proto::Snapshot* Find(const std::string& name) const;

  // timeline; every snapshot's journal_seq must be set
  void StartTimeline(proto::Snapshot base);
  void AddPeriodic(proto::Snapshot snapshot);
  void AddRecord(JournalRecord record) { records_.push_back(std::move(record)); }
  // Forgets the records from `seq` on (a batch the disk journal refused).
  void DropRecordsFrom(int64_t seq) {
    while (!records_.empty() && records_.back().seq >= seq) records_.pop_back();
  }
  int64_t base_step() const { return snapshots_.empty() ? 0 : snapshots_.front().step(); }

  // How to reach the state after `step` steps: the latest snapshot at or
  // before it that no record applied at `step` or later precedes, and the
  // records between it and `step`. Fails when `step` is outside
  // [base_step, current_step].
  struct Plan {
    const proto::Snapshot* from = nullptr;
    std::vector<const JournalRecord*> records;
  };
  Status PlanRewind(int64_t step, int64_t current_step, Plan* plan) const;
  // Forgets what lies after `step` (records applied at it or later, later
  // snapshots): the run continues from there on a new course.
  void TruncateAfter(int64_t step);

  size_t snapshot_count() const { return snapshots_.size(); }
  size_t record_count() const { return records_.size(); }

 private:
  size_t FirstRecordAtOrAfter(int64_t step) const;
  int64_t SeqAt(size_t record_index, int64_t fallback) const;

  int max_periodic_;
  std::map<std::string, proto::Snapshot> slots_;
  std::deque<proto::Snapshot> snapshots_;  // base first, then ascending
  std::deque<JournalRecord> records_;      // ascending seq (and step)
};

}  // namespace contactsim
