"""The live source of the viewer: a contactsim.Client like any other.

STATE, CONTACTS and STATUS come from the client's latest-message cache, so
the bridge decodes only the STATEs it sends (the latest when the page is
ready for one, docs/viewer.md), and reads their bodies with numpy
(frames.read_state). Shapes, masses and joints are not in STATE:
the bridge asks the server for a snapshot file (SNAPSHOT with a path, which
changes nothing in the world) whenever the set of body ids changes, the
clock goes back, a reply tells of a joint added or removed, or a sensor
reading names a sensor it has not seen. The models' mesh files are served
from their folders only (meshes.py); ray casts and sensor fans come from
rays.py.
"""
import os
import tempfile
import threading
import time
import warnings

import numpy as np

from ..protocol import METHODS  # the contact methods the server registers; STATUS adds the active one
from .catalog import read_catalog
from .commands import run_command
from .frames import rays_frame
from .meshes import MeshFiles
from .rays import RayWatch, range_rays, unknown_sensors

RETRY_S = 2.0   # s between snapshot attempts after one failed


class LiveSource:
    mode = "live"

    def __init__(self, client, scenes_dir=None):
        self.client = client
        self.scenes_dir = scenes_dir
        self._tmp = tempfile.TemporaryDirectory(prefix="contactsim-viewer-")
        self.catalog = {"bodies": [], "joints": []}
        self.meshes = MeshFiles()
        self.rays = RayWatch(client)
        self.catalog_version = 0
        self._catalog_ids = None
        self._last_step = None
        self._dirty = threading.Event()
        self._dirty.set()
        self._refresh_lock = threading.Lock()
        self._retry_at = 0.0
        self._remove_reply_cb = client.on_reply(self._on_reply)

    def close(self):
        self._remove_reply_cb()
        self.rays.close()
        self._tmp.cleanup()

    def hello(self):
        scenes = []
        if self.scenes_dir and os.path.isdir(self.scenes_dir):
            scenes = sorted(os.path.join(self.scenes_dir, f) for f in os.listdir(self.scenes_dir)
                            if f.endswith(".pbtxt"))
        return {"type": "hello", "mode": "live", "methods": list(METHODS), "scenes": scenes,
                "prefix": self.client.prefix, "signed": self.client.signs}

    def _on_reply(self, reply):
        # runs on the client's LCM thread: only flag, the refresh sends a command
        if reply.code == 0 and reply.client_id != self.client.client_id and " joint" in reply.message:
            self._dirty.set()

    def note_state(self, step, ids):
        """Flags a catalog refresh when the body ids (an array) or the timeline changed."""
        if not np.array_equal(ids, self._catalog_ids) or (self._last_step is not None and step < self._last_step):
            self._dirty.set()
        self._last_step = step

    def refresh_catalog(self):
        """Reads a fresh snapshot when flagged (blocking: run off the event
        loop); True when the catalog changed."""
        if (not self._dirty.is_set() or time.monotonic() < self._retry_at
                or not self._refresh_lock.acquire(blocking=False)):
            return False
        try:
            self._dirty.clear()
            path = os.path.join(self._tmp.name, "catalog.snapshot")
            try:
                self.client.snapshot(path=path)
                catalog = read_catalog(path)
            except Exception as e:  # noqa: BLE001 - a remote server cannot write our file: draw markers
                warnings.warn("contactsim-viewer: no shapes from a snapshot (%s); drawing markers" % e)
                self._retry_at = time.monotonic() + RETRY_S   # a busy server may answer later
                self._dirty.set()
                return False
            self.meshes.add_urls(catalog)
            self.catalog = catalog
            self._catalog_ids = np.array([b["id"] for b in catalog["bodies"]], dtype=np.int64)
            self.catalog_version += 1
            return True
        finally:
            self._refresh_lock.release()

    def cast_frame(self):
        """(count, RAYS frame) of the newest answered ray cast, or (0, None)."""
        count, latest = self.rays.newest()
        if latest is None:
            return 0, None
        step, origins, ends, hit, normals = latest
        return count, rays_frame(step, 0, np.zeros(len(hit)), origins, ends, hit, normals)

    def sensors_frame(self, reading):
        """The RAYS frame of a SENSORS reading's range fans."""
        if unknown_sensors(reading, self.catalog):
            self._dirty.set()   # its origin is in the next snapshot
        return rays_frame(reading.step, 1, *range_rays(reading, self.catalog))

    def body_info(self, body_id):
        """Catalog entry of a body plus its latest velocities (page clicks)."""
        info = next((dict(b) for b in self.catalog["bodies"] if b["id"] == body_id), {"id": body_id})
        st = self.client.state()
        if st is not None and body_id in st.bodies:
            b = st.bodies[body_id]
            info.update(position=b.position.tolist(), linear_velocity=b.linear_velocity.tolist(),
                        angular_velocity=b.angular_velocity.tolist())
        return info

    def command(self, msg):
        """Runs one page command through the client (blocking); returns the reply text."""
        text = run_command(self.client, msg)
        if msg.get("cmd") in ("reset", "load", "restore", "rewind"):
            self._dirty.set()
        return text
