// SimServer's SNAPSHOT, RESTORE and REWIND (docs/snapshots.md): a copy of
// the world into a named slot or a file, a world back from one, and a
// re-simulation to an earlier step (timeline.cpp). Simulation thread.
#include "service/scene/snapshot.h"
#include "service/scene/snapshot_manifolds.h"
#include "service/server/sim_server.h"

namespace contactsim {

proto::Snapshot SimServer::SaveState() const {
  proto::Snapshot s;
  SaveSnapshot(world_, *method_, &s);
  SaveManifolds(detector_.manifolds(), &s);
  return s;
}

Outcome SimServer::ApplySnapshotCommand(Command& cmd) {
  using K = Command::Kind;
  const std::string target = cmd.snapshot_name.empty() ? "file " + cmd.snapshot_path : "\"" + cmd.snapshot_name + "\"";
  Status st;
  if (cmd.kind == K::kSnapshot) {
    proto::Snapshot s = SaveState();
    s.set_journal_seq(batch_.journal().next_seq());
    if (!cmd.snapshot_path.empty()) {
      // a replay must not overwrite the recorded run's file (a RESTORE from it comes later)
      if (options_.write_files) st = WriteSnapshotFile(cmd.snapshot_path, s, options_.journal_fsync == FsyncPolicy::kAlways);
    } else {
      batch_.history().Put(cmd.snapshot_name, std::move(s));
    }
    if (!st.ok()) return Outcome::Failed(st);
    return Outcome::Done("snapshot " + target + " at step " + std::to_string(world_.step), false);
  }
  if (cmd.kind == K::kRewind) {
    const int64_t from = world_.step;
    st = Rewind(cmd.target_step, &cmd);
    if (!st.ok()) return Outcome::Failed(st);
    CancelStepCommands("rewind");
    ClearFault();
    return Outcome::Done("rewound from step " + std::to_string(from) + " to step " + std::to_string(world_.step), true);
  }
  proto::Snapshot loaded;
  const proto::Snapshot* s = nullptr;
  if (!cmd.snapshot_path.empty()) {
    st = ReadSnapshotFile(cmd.snapshot_path, &loaded);
    s = &loaded;
  } else if ((s = batch_.history().Find(cmd.snapshot_name)) == nullptr) {
    st = Status::NotFound("no snapshot named \"" + cmd.snapshot_name + "\"");
  }
  World world;
  std::shared_ptr<ContactMethod> method;
  std::vector<CachedManifold> manifolds;
  if (st.ok()) st = LoadSnapshot(*s, &world, &method);
  if (st.ok()) st = ReadManifolds(*s, &manifolds);
  if (!st.ok()) return Outcome::Failed(st);
  CancelStepCommands("restore");
  ReplaceWorld(std::move(world), std::move(method), std::move(manifolds));
  StartOver();
  return Outcome::Done("restored " + target + " at step " + std::to_string(world_.step), true);
}

}  // namespace contactsim
