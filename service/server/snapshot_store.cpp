#include "service/server/snapshot_store.h"

#include <algorithm>

namespace contactsim {

const proto::Snapshot* SnapshotStore::Find(const std::string& name) const {
  const auto it = slots_.find(name);
  return it == slots_.end() ? nullptr : &it->second;
}

void SnapshotStore::StartTimeline(proto::Snapshot base) {
  snapshots_.clear();
  records_.clear();
  snapshots_.push_back(std::move(base));
}

void SnapshotStore::AddPeriodic(proto::Snapshot snapshot) {
  snapshots_.push_back(std::move(snapshot));
  // Beyond max_periodic_ periodic snapshots the oldest snapshot goes, and
  // with it the records that only it needed (those before the next one's
  // journal_seq are in that snapshot's state): the next snapshot becomes the
  // base, so a long run's history stays bounded (max_periodic_ + 1
  // snapshots and the records since the oldest) and REWIND reaches back
  // max_periodic_ snapshot periods.
  while (static_cast<int>(snapshots_.size()) > max_periodic_ + 1) {
    snapshots_.pop_front();
    const int64_t kept_from = snapshots_.front().journal_seq();
    while (!records_.empty() && records_.front().seq < kept_from) records_.pop_front();
  }
}

size_t SnapshotStore::FirstRecordAtOrAfter(int64_t step) const {
  const auto it = std::lower_bound(records_.begin(), records_.end(), step,
                                   [](const JournalRecord& r, int64_t s) { return r.step < s; });
  return static_cast<size_t>(it - records_.begin());
}

int64_t SnapshotStore::SeqAt(size_t i, int64_t fallback) const {
  return i < records_.size() ? records_[i].seq : fallback;
}

Status SnapshotStore::PlanRewind(int64_t step, int64_t current_step, Plan* plan) const {
  if (snapshots_.empty() || step < base_step() || step > current_step) {
    return Status::InvalidArgument("step must be in [" + std::to_string(base_step()) + ", " +
                                   std::to_string(current_step) +
                                   "] (the oldest state kept: the last reset, load or restore, or the oldest of the "
                                   "max_snapshots periodic snapshots), got " +
                                   std::to_string(step));
  }
  const size_t end = FirstRecordAtOrAfter(step);
  const int64_t end_seq = SeqAt(end, INT64_MAX);
  plan->from = nullptr;
  for (const proto::Snapshot& s : snapshots_) {
    if (s.step() <= step && s.journal_seq() <= end_seq) plan->from = &s;
  }
  if (plan->from == nullptr) return Status::FailedPrecondition("no snapshot before step " + std::to_string(step));
  plan->records.clear();
  for (size_t i = 0; i < end; ++i) {
    if (records_[i].seq >= plan->from->journal_seq()) plan->records.push_back(&records_[i]);
  }
  return Status::Ok();
}

void SnapshotStore::TruncateAfter(int64_t step) {
  const size_t end = FirstRecordAtOrAfter(step);
  const int64_t end_seq = SeqAt(end, INT64_MAX);
  records_.erase(records_.begin() + static_cast<std::ptrdiff_t>(end), records_.end());
  // the base always stays (its step is <= step by PlanRewind's check)
  for (size_t i = snapshots_.size(); i-- > 1;) {
    if (snapshots_[i].step() > step || snapshots_[i].journal_seq() > end_seq) snapshots_.erase(snapshots_.begin() + i);
  }
}

}  // namespace contactsim
