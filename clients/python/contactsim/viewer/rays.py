"""What the page draws of rays: every client's ray casts (RAY_CAST with its
answer on RAY_HITS) and the range sensors' fans (SENSORS), as RAYS frames
(frames.py). A ray is drawn from its origin to its hit point, or to its
farthest point when it hits nothing; a cast's hits carry the surface's
normal, which the page draws as a short line.

A ray_hits_t carries the hit points but not the rays, so the watch also
reads every RAY_CAST and pairs the two by (client_id, request_id). A range
reading carries its points; the rays start at the sensor's origin in its
body's frame (the catalog's range_sensors, from the snapshot), which the
page places with the body's pose."""
import threading

import numpy as np

from .. import ray_cast_t

KEEP_CASTS = 64   # casts whose answers have not come yet


class RayWatch:
    def __init__(self, client):
        self._lock = threading.Lock()
        self._casts = {}          # (client_id, request_id) -> origins (n, 3), directions (n, 3), max (n,)
        self.latest = None        # the newest answered cast: (step, origins, ends, hit (n,), normals), (n, 3) each
        self.count = 0            # answered casts seen
        self._removers = [client.on_command("RAY_CAST", ray_cast_t, self._on_cast),
                          client.on_ray_hits(self._on_hits)]

    def close(self):
        for remove in self._removers:
            remove()

    def newest(self):
        """(answered casts seen, the newest one's (step, origins, ends, hit, normals) or None), read together."""
        with self._lock:
            return self.count, self.latest

    def _on_cast(self, msg):
        n = msg.num_rays
        d = np.array(msg.directions, dtype=np.float64).reshape(n, 3)
        norms = np.linalg.norm(d, axis=1, keepdims=True)
        with self._lock:
            self._casts[(msg.client_id, msg.request_id)] = (
                np.array(msg.origins, dtype=np.float64).reshape(n, 3),
                d / np.where(norms > 0, norms, 1.0), np.array(msg.max_distances, dtype=np.float64).reshape(n))
            while len(self._casts) > KEEP_CASTS:
                self._casts.pop(next(iter(self._casts)))

    def _on_hits(self, msg):
        with self._lock:
            cast = self._casts.pop((msg.client_id, msg.request_id), None)
            if cast is None or len(cast[0]) != msg.num_rays:
                return
            origins, directions, far = cast
            hit = np.array(list(msg.hit), dtype=bool)
            ends = np.where(hit[:, None], np.array(msg.points, dtype=np.float64).reshape(-1, 3),
                            origins + directions * far[:, None])
            self.latest = (msg.step, origins, ends, hit, np.array(msg.normals, dtype=np.float64).reshape(-1, 3))
            self.count += 1


def range_rays(sensors, catalog):
    """(body ids (n,), origins in the body frames (n, 3), ends in the world
    (n, 3), hit (n,)) of every range sensor's rays in a Sensors reading; a
    sensor the catalog does not know yet starts at its body's centre."""
    origin_of = {r["name"]: r["origin"] for r in catalog.get("range_sensors", [])}
    bodies, origins, ends, hits = [], [], [], []
    for name, r in sensors.ranges.items():
        n = len(r["hit"])
        bodies.append(np.full(n, r["body_id"], dtype=np.float64))
        origins.append(np.tile(np.asarray(origin_of.get(name, (0.0, 0.0, 0.0)), dtype=np.float64), (n, 1)))
        ends.append(r["points"])
        hits.append(r["hit"])
    if not bodies:
        return np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0, dtype=bool)
    return np.concatenate(bodies), np.vstack(origins), np.vstack(ends), np.concatenate(hits)


def unknown_sensors(sensors, catalog):
    """True when a reading names a range sensor the catalog has not seen."""
    known = {r["name"] for r in catalog.get("range_sensors", [])}
    return any(name not in known for name in sensors.ranges)
