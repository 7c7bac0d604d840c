"""Ray casts and sensors of the Client (docs/protocol.md, "Ray casts" and
"Sensors").

``ray_cast`` sends a batch of rays on <prefix>_RAY_CAST and returns the
server's answer from <prefix>_RAY_HITS as numpy arrays. A range sensor (a
fixed fan of rays from a body, a simple lidar) and a contact sensor (the
contact wrench a body received in a step) publish their readings on
<prefix>_SENSORS with every STATE; ``sensors()`` is the latest reading,
``wait_for_sensors`` waits for one, ``on_sensors`` calls back with each.
"""
import threading

import numpy as np

from . import ray_cast_t, ray_hits_t, sensor_cmd_t, sensors_t
from ._fields import vector
from .errors import TimeoutError


class RayHits:
    """The answer to one ray cast: numpy arrays of N rays. hit (bool),
    body_ids (int64, 0 for a miss), points and normals (N x 3, m and unit,
    world frame), distances (m); a ray starting inside a body hits it at
    distance 0 with the normal against the ray."""

    def __init__(self, msg):
        n = msg.num_rays
        self.step = msg.step
        self.time = msg.time
        # lcm-gen decodes a boolean array as a map object
        self.hit = np.array(list(msg.hit), dtype=bool).reshape(n)
        self.body_ids = np.array(msg.body_ids, dtype=np.int64).reshape(n)
        self.points = np.array(msg.points, dtype=np.float64).reshape(n, 3)
        self.normals = np.array(msg.normals, dtype=np.float64).reshape(n, 3)
        self.distances = np.array(msg.distances, dtype=np.float64).reshape(n)

    def __iter__(self):  # hit, body_ids, points, normals, distances = sim.ray_cast(...)
        return iter((self.hit, self.body_ids, self.points, self.normals, self.distances))


class Sensors:
    """One SENSORS message: ``ranges[name]`` and ``contacts[name]`` as dicts
    of numpy arrays (a range sensor: hit, body_ids, distances, points; a
    contact sensor: body_id, num_contacts, normal_force, friction_force,
    torque in N and N m, world frame)."""

    def __init__(self, msg):
        self.step = msg.step
        self.time = msg.time
        self.ranges = {}
        for r in msg.ranges:
            n = r.num_rays
            self.ranges[r.name] = {
                "body_id": r.body_id,
                "hit": np.array(list(r.hit), dtype=bool).reshape(n),
                "body_ids": np.array(r.hit_body_ids, dtype=np.int64).reshape(n),
                "distances": np.array(r.distances, dtype=np.float64).reshape(n),
                "points": np.array(r.points, dtype=np.float64).reshape(n, 3),
            }
        self.contacts = {}
        for c in msg.contacts:
            self.contacts[c.name] = {
                "body_id": c.body_id,
                "num_contacts": c.num_contacts,
                "normal_force": np.array(c.normal_force),
                "friction_force": np.array(c.friction_force),
                "torque": np.array(c.torque),
            }


def _rows(value, n, field):
    a = np.asarray(value, dtype=np.float64)
    if a.ndim == 1:
        a = a.reshape(1, -1)
    if a.ndim != 2 or a.shape[1] != 3 or (n is not None and a.shape[0] != n):
        raise ValueError("%s must be an N x 3 array%s, got shape %s"
                         % (field, "" if n is None else " with N = %d" % n, np.shape(value)))
    return a


class SensorCommands:
    """Mixin of Client: needs ``_send``, ``_lc``, ``channels``, ``_subs``,
    ``_lock``, ``_decode`` and ``client_id``."""

    def _init_sensors(self):
        self._ray_hits = {}            # request id -> ray_hits_t, until ray_cast takes it
        self._ray_cond = threading.Condition(self._lock)
        self._sensors_msg = None
        self._sensors_seq = 0
        self._sensors_cond = threading.Condition(self._lock)
        self._callbacks["sensors"] = []
        self._callbacks["ray_hits"] = []
        return [self._lc.subscribe(self.channels["RAY_HITS"], self._on_ray_hits_msg),
                self._lc.subscribe(self.channels["SENSORS"], self._on_sensors_msg)]

    def _on_ray_hits_msg(self, channel, data):
        msg = self._decode(channel, data, ray_hits_t)
        if msg is None:
            return
        self._call("ray_hits", msg)
        if msg.client_id != self.client_id:
            return
        with self._ray_cond:
            self._ray_hits[msg.request_id] = msg
            while len(self._ray_hits) > 64:  # answers nobody waits for any more
                self._ray_hits.pop(next(iter(self._ray_hits)))
            self._ray_cond.notify_all()

    def _on_sensors_msg(self, channel, data):
        msg = self._decode(channel, data, sensors_t)
        if msg is None:
            return
        reading = Sensors(msg)
        with self._sensors_cond:
            self._sensors_msg = reading
            self._sensors_seq += 1
            self._sensors_cond.notify_all()
        self._call("sensors", reading)

    def ray_cast(self, origins, directions, max_distance, *, ignore=(), mask=None, timeout=None):
        """Casts N rays (origins and directions: N x 3 arrays, world frame;
        max_distance: a number or N numbers, m) and returns a RayHits, which
        unpacks as (hit, body_ids, points, normals, distances). Rays pass
        through the bodies in ``ignore``; with ``mask`` (32 bits) only bodies
        whose collision category shares a bit with it are hit. Bad rays
        raise CommandError."""
        o = _rows(origins, None, "origins")
        d = _rows(directions, o.shape[0], "directions")
        n = o.shape[0]
        dist = np.broadcast_to(np.asarray(max_distance, dtype=np.float64), (n,))
        m = ray_cast_t()
        m.num_rays = n
        m.origins = o.tolist()
        m.directions = d.tolist()
        m.max_distances = [float(x) for x in dist]
        m.ignore_ids = [int(i) for i in ignore]
        m.num_ignore = len(m.ignore_ids)
        m.collision_mask = 0 if mask is None else int(mask)
        self._send("RAY_CAST", m, timeout=timeout)  # sets m.request_id
        with self._ray_cond:
            # the answer is published before the reply; allow for reordering
            self._ray_cond.wait_for(lambda: m.request_id in self._ray_hits,
                                    timeout=self.timeout if timeout is None else timeout)
            msg = self._ray_hits.pop(m.request_id, None)
        if msg is None:
            raise TimeoutError("no RAY_HITS for ray cast request %d" % m.request_id)
        return RayHits(msg)

    def add_range_sensor(self, body_id, name, directions, max_distance, *, origin=(0, 0, 0)):
        """Attaches a fan of rays to a body: ``directions`` (N x 3, body
        frame) from ``origin`` (m, body frame), each reading up to
        ``max_distance`` m; read on SENSORS as ``sensors().ranges[name]``."""
        d = _rows(directions, None, "directions")
        m = self._sensor(sensor_cmd_t.ADD_RANGE, name, body_id)
        m.origin = vector(origin, 3, "origin")
        m.num_rays = d.shape[0]
        m.directions = d.tolist()
        m.max_distance = float(max_distance)
        return self._send("SENSOR_CMD", m)

    def add_contact_sensor(self, body_id, name):
        """Reads the contact wrench ``body_id`` receives each step, as
        ``sensors().contacts[name]``; refused by a method that does not
        report contact forces."""
        return self._send("SENSOR_CMD", self._sensor(sensor_cmd_t.ADD_CONTACT, name, body_id))

    def remove_sensor(self, name):
        return self._send("SENSOR_CMD", self._sensor(sensor_cmd_t.REMOVE, name, 0))

    def _sensor(self, op, name, body_id):
        m = sensor_cmd_t()
        m.op = op
        m.name = str(name)
        m.body_id = int(body_id)
        m.origin = [0.0, 0.0, 0.0]
        m.num_rays = 0
        m.directions = []
        m.max_distance = 0.0
        return m

    def sensors(self):
        """The latest SENSORS reading, or None before any."""
        with self._lock:
            return self._sensors_msg

    def wait_for_sensors(self, predicate=None, timeout=None):
        """Waits for a SENSORS reading after this call (satisfying predicate,
        when given) and returns it."""
        self._check_thread()
        timeout = self.timeout if timeout is None else timeout
        with self._sensors_cond:
            seq = self._sensors_seq

            def ready():
                return self._sensors_seq > seq and (predicate is None or predicate(self._sensors_msg))
            if not self._sensors_cond.wait_for(ready, timeout=timeout):
                raise TimeoutError("no SENSORS reading within %gs" % timeout)
            return self._sensors_msg

    def on_ray_hits(self, callback):
        """Calls callback(ray_hits_t) for every RAY_HITS, any client's; returns a remover."""
        return self._add_callback("ray_hits", callback)

    def on_sensors(self, callback):
        """Calls callback(Sensors) with each reading; returns a remover."""
        return self._add_callback("sensors", callback)
