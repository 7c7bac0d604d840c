"""Snapshot, restore and rewind commands of the contactsim Client
(docs/snapshots.md). A mixin: ``Client`` inherits these methods."""
from . import scene_cmd_t


class SnapshotCommands:
    """SNAPSHOT, RESTORE and REWIND; each returns the server's Reply and
    raises CommandError with its message when refused."""

    def _snapshot_target(self, op, name, path):
        if (name is None) == (path is None):
            raise ValueError("give exactly one of name or path")
        m = self._scene(op)
        m.name = name or ""
        m.path = str(path or "")
        return m

    def snapshot(self, name=None, *, path=None):
        """Saves the world (bodies, clock, contact method and its caches) to
        the server's slot ``name`` or to the file ``path`` on its host."""
        return self._send("SCENE_CMD", self._snapshot_target(scene_cmd_t.SNAPSHOT, name, path))

    def restore(self, name=None, *, path=None):
        """Replaces the world by a snapshot: the run continues exactly as it
        did from there. Starts a new timeline for rewind."""
        return self._send("SCENE_CMD", self._snapshot_target(scene_cmd_t.RESTORE, name, path))

    def rewind(self, step, *, timeout=None):
        """Takes the world back to its state after ``step`` steps (nearest
        snapshot before it, then the journal replayed forward); what came
        after is forgotten. ``step`` must lie in the current timeline (since
        the last reset, scene load or restore)."""
        m = self._scene(scene_cmd_t.REWIND)
        m.target_step = int(step)
        return self._send("SCENE_CMD", m, timeout=timeout)
