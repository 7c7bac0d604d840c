"""A job: a world to start from, a contact method, a number of steps and
what to collect. Plain data, so that Ray can ship it to any node.

The world travels as bytes, not as a path: a scene file's text or a
snapshot's bytes, written to the worker's own folder before loading, so a
worker on another machine needs no shared file system.
"""
import dataclasses
from pathlib import Path

# what a job can collect; "hash" and "metrics" are cheap, "trajectory" needs `bodies`
COLLECT = ("hash", "metrics", "trajectory")


@dataclasses.dataclass
class Job:
    """``scene``: a scene file path (read on the driver) or its text;
    ``snapshot``: a snapshot file path or its bytes (exactly one of the two).
    ``method`` and ``params``: the contact method to run (None: the scene's
    or snapshot's). ``bodies``: names whose positions make the trajectory.
    ``tag``: anything that identifies the job in its row."""

    scene: object = None
    snapshot: object = None
    method: str = None
    params: dict = dataclasses.field(default_factory=dict)
    steps: int = 240
    collect: tuple = ("hash", "metrics")
    bodies: tuple = ()
    tag: object = None

    def __post_init__(self):
        if (self.scene is None) == (self.snapshot is None):
            raise ValueError("a job needs exactly one of scene or snapshot")
        unknown = set(self.collect) - set(COLLECT)
        if unknown:
            raise ValueError("collect: unknown %s (known: %s)" % (sorted(unknown), ", ".join(COLLECT)))
        if int(self.steps) < 1:
            raise ValueError("steps must be >= 1, got %r" % (self.steps,))
        if "trajectory" in self.collect and not self.bodies:
            raise ValueError("collect trajectory needs the names of the bodies to follow (bodies=...)")

    def packed(self):
        """This job with its world as bytes (scene text encoded, files read)."""
        scene, snapshot = self.scene, self.snapshot
        if isinstance(scene, (str, Path)) and _is_file(scene):
            scene = Path(scene).read_text()
        if isinstance(snapshot, (str, Path)):
            snapshot = Path(snapshot).read_bytes()
        return dataclasses.replace(self, scene=scene, snapshot=snapshot)

    def describe(self):
        """The row's identifying columns."""
        return {"tag": self.tag, "method": self.method or "", "params": _params_text(self.params),
                "steps": int(self.steps)}


def _is_file(value):
    # scene text has newlines or braces; a path has neither
    text = str(value)
    return "\n" not in text and "{" not in text and Path(text).is_file()


def _params_text(params):
    return " ".join("%s=%s" % kv for kv in sorted((params or {}).items()))
