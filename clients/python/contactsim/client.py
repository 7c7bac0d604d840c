"""The contactsim client: commands with replies, and the latest STATE,
CONTACTS and STATUS, over LCM.

A background thread runs ``lcm.handle_timeout``; callbacks (``on_state``,
``on_contacts``, ``on_status``, ``on_reply``) run on it, so they must be quick
and must not send commands (that would wait for a reply the same thread has to
receive: a RuntimeError says so).

With an auth key (``auth_key_file``, or $CONTACTSIM_AUTH_KEY_FILE) every
message the client publishes is signed, and server messages whose signature
fails are dropped and counted (``auth_failures``; docs/protocol.md,
"Authentication").
"""
import os
import socket
import struct
import threading
import time
import uuid
import warnings

import lcm
import numpy as np

from . import body_cmd_t, contacts_t, model_info_t, progress_t, protocol, reply_t, scene_cmd_t, state_t, status_t
from .auth import DEFAULT_WINDOW_S, Authenticator, unsigned_size
from ._fields import vector as _vec
from ._body_fields import mass_properties as _mass_properties, part as _part
from .errors import CommandError, TimeoutError
from .lockstep import LockstepCommands
from .snapshots import SnapshotCommands
from .filters import FilterCommands, fill_filter
from .joints import JointCommands
from .sensors import SensorCommands
from .models import ModelCommands
from .actuators import ActuatorCommands
from .surfaces import SurfaceCommands
from .state import MODE_NAMES, Contacts, State, Status, reply_from_msg

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=8388608"
MODES = {name: mode for mode, name in MODE_NAMES.items()}  # SET_MODE uses status_t's values
_STATE_FP = state_t._get_packed_fingerprint()
_CONTACTS_FP = contacts_t._get_packed_fingerprint()


def default_url():
    """LCM_DEFAULT_URL when set, else the project default (host-only, 8 MiB buffer)."""
    return os.environ.get("LCM_DEFAULT_URL") or DEFAULT_URL


def _param_text(value):
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


class _Pending:
    __slots__ = ("event", "reply", "heard", "on_progress")

    def __init__(self, on_progress=None):
        self.event = threading.Event()
        self.reply = None
        self.heard = time.monotonic()  # the last sign of the server working on it
        self.on_progress = on_progress


class _Waiter:
    __slots__ = ("predicate", "event", "result", "error")

    def __init__(self, predicate):
        self.predicate = predicate
        self.event = threading.Event()
        self.result = None
        self.error = None


# Messages LCM may hold per channel before this client handles them.
SUBSCRIPTION_QUEUE_CAPACITY = 100000


class Client(SnapshotCommands, LockstepCommands, JointCommands, FilterCommands, SensorCommands,
             ModelCommands, ActuatorCommands, SurfaceCommands):
    """A connection to one contactsim server (one LCM URL and channel prefix).

    ``url`` None: LCM_DEFAULT_URL, else the project default. ``client_id``
    None: a unique "py-<host>-<pid>-<random>". ``timeout`` (s) bounds the
    wait for each reply. ``auth_key_file``: sign commands and check the
    server's signatures with this key (None: $CONTACTSIM_AUTH_KEY_FILE; ""
    or unset: no signing); a bad key file raises ``contactsim.AuthKeyError``.
    ``auth_window_s``: how far (s) a signed seq may be from this clock. Use
    as a context manager, or call ``close()``.
    """

    def __init__(self, url=None, prefix="CONTACTSIM", client_id=None, timeout=2.0,
                 auth_key_file=None, auth_window_s=DEFAULT_WINDOW_S):
        self._auth = Authenticator.from_key_file(auth_key_file, auth_window_s)  # before LCM: may raise
        self.url = url or default_url()
        self.prefix = prefix
        self.client_id = client_id or "py-%s-%d-%s" % (
            socket.gethostname(), os.getpid(), uuid.uuid4().hex[:6])
        self.timeout = timeout
        self.channels = protocol.channel_names(prefix)
        self._lock = threading.Lock()
        self._cond = threading.Condition(self._lock)
        self._request_id = 0
        self._pending = {}
        self._state_bytes = None      # latest STATE payload, decoded lazily
        self._state_obj = None
        self._state_step = None
        self._state_seq = 0           # number of STATEs received
        self._contacts_bytes = None   # latest CONTACTS payload, decoded lazily like STATE
        self._contacts_msg = None
        self._contacts_seq = 0
        self._status = None
        self._status_seq = 0
        self._model_info = None       # latest MODEL_INFO (models.py)
        self._model_info_seq = 0
        self._callbacks = {"state": [], "contacts": [], "status": [], "reply": []}
        self._state_waiters = []
        self._status_waiters = []
        self._lc = lcm.LCM(self.url)
        self._subs = [
            self._lc.subscribe(self.channels["REPLY"], self._on_reply_msg),
            self._lc.subscribe(self.channels["STATE"], self._on_state_msg),
            self._lc.subscribe(self.channels["CONTACTS"], self._on_contacts_msg),
            self._lc.subscribe(self.channels["STATUS"], self._on_status_msg),
            self._lc.subscribe(self.channels["PROGRESS"], self._on_progress_msg),
            self._lc.subscribe(self.channels["MODEL_INFO"], self._on_model_info_msg),
        ]
        self._subs += self._init_sensors()
        self._subs += self._init_actuators()
        # LCM keeps at most 30 undelivered messages per subscription and drops
        # the rest; a free-running server sends STATE in bursts far larger.
        for sub in self._subs:
            sub.set_queue_capacity(SUBSCRIPTION_QUEUE_CAPACITY)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="contactsim-lcm", daemon=True)
        self._thread.start()

    # ------------------------------------------------------------------ life
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        """Stops the receive thread and unsubscribes; pending commands time out."""
        if self._stop.is_set():
            return
        self._stop.set()
        if threading.current_thread() is not self._thread:
            self._thread.join(timeout=2.0)
        for s in self._subs:
            try:
                self._lc.unsubscribe(s)
            except Exception:  # noqa: BLE001 - best effort at shutdown
                pass
        self._subs = []

    def _run(self):
        while not self._stop.is_set():
            try:
                self._lc.handle_timeout(50)
            except Exception as e:  # noqa: BLE001 - keep receiving
                warnings.warn("contactsim: LCM receive error: %s" % e)

    # ------------------------------------------------------------ signing
    @property
    def signs(self):
        """True when this client signs its messages (an auth key is set)."""
        return self._auth is not None

    @property
    def auth_failures(self):
        """Server messages dropped because their signature, freshness or seq failed."""
        return self._auth.failures if self._auth else 0

    @property
    def last_auth_failure(self):
        """Why the last one was dropped ("<channel>: <why>"), "" before any."""
        return self._auth.last_failure if self._auth else ""

    def _publish(self, channel, payload):
        if self._auth is not None:
            payload = self._auth.sign(channel, payload)
        self._lc.publish(channel, payload)

    def _unwrap(self, channel, data):
        """The payload of a received message (None: dropped): verified with a
        key, else stripped of any trailer."""
        if self._auth is not None:
            return self._auth.unwrap(channel, data)
        return data[:unsigned_size(data)]

    def _call(self, kind, obj):
        for cb in list(self._callbacks[kind]):
            try:
                cb(obj)
            except Exception as e:  # noqa: BLE001 - a bad callback must not stop the thread
                warnings.warn("contactsim: %s callback raised %r" % (kind, e))

    # -------------------------------------------------------------- handlers
    def _decode(self, channel, data, msg_type):
        """The received message, or None when it fails its check or does not decode."""
        data = self._unwrap(channel, data)
        if data is None:
            return None
        try:
            return msg_type.decode(data)
        except Exception:  # noqa: BLE001 - not ours to judge
            return None

    def _on_reply_msg(self, channel, data):
        msg = self._decode(channel, data, reply_t)
        if msg is None:
            return
        if msg.client_id == self.client_id:
            with self._lock:
                slot = self._pending.pop(msg.request_id, None)
            if slot is not None:
                slot.reply = msg
                slot.event.set()
        self._call("reply", msg)

    def _on_progress_msg(self, channel, data):
        msg = self._decode(channel, data, progress_t)
        if msg is None or msg.client_id != self.client_id:
            return
        with self._lock:
            slot = self._pending.get(msg.request_id)
        if slot is None:
            return
        slot.heard = time.monotonic()
        if slot.on_progress is not None:
            try:
                slot.on_progress(msg)
            except Exception as e:  # noqa: BLE001 - a bad callback must not stop the thread
                warnings.warn("contactsim: progress callback raised %r" % (e,))

    def _on_state_msg(self, channel, data):
        data = self._unwrap(channel, data)
        if data is None or len(data) < 24 or data[:8] != _STATE_FP:
            return
        _, step = struct.unpack_from(">dq", data, 8)
        with self._lock:
            self._state_bytes = data
            self._state_obj = None
            waiters = list(self._state_waiters)
        if waiters or self._callbacks["state"]:
            st = self._latest_state_obj()
            if st is not None:
                self._call("state", st)
                self._resolve(waiters, self._state_waiters, st)
        # step() wakes last: when it returns, on_state callbacks have seen the state
        with self._cond:
            self._state_step = step
            self._state_seq += 1
            self._cond.notify_all()

    def _on_contacts_msg(self, channel, data):
        # thousands of contacts take tens of ms to decode: only when asked for
        data = self._unwrap(channel, data)
        if data is None or data[:8] != _CONTACTS_FP:
            return
        with self._lock:
            self._contacts_bytes = data
            self._contacts_msg = None
            self._contacts_seq += 1
        if self._callbacks["contacts"]:
            msg = self._latest_contacts_msg()
            if msg is not None:
                self._call("contacts", Contacts(msg))

    def _latest_contacts_msg(self):
        with self._lock:
            if self._contacts_msg is not None or self._contacts_bytes is None:
                return self._contacts_msg
            data = self._contacts_bytes
        try:
            msg = contacts_t.decode(data)
        except Exception:  # noqa: BLE001 - a corrupt CONTACTS is skipped
            return None
        with self._lock:
            if self._contacts_bytes is data:
                self._contacts_msg = msg
        return msg

    def _on_status_msg(self, channel, data):
        msg = self._decode(channel, data, status_t)
        if msg is None:
            return
        st = Status(msg)
        with self._cond:
            self._status = st
            self._status_seq += 1
            waiters = list(self._status_waiters)
            self._cond.notify_all()
        self._call("status", st)
        self._resolve(waiters, self._status_waiters, st)

    def _on_model_info_msg(self, channel, data):
        msg = self._decode(channel, data, model_info_t)
        if msg is None:
            return
        with self._cond:
            self._model_info = msg
            self._model_info_seq += 1
            self._cond.notify_all()

    def _resolve(self, waiters, registry, obj):
        for w in waiters:
            try:
                ok = w.predicate is None or w.predicate(obj)
            except Exception as e:  # noqa: BLE001 - report to the waiting thread
                w.error, ok = e, True
            if ok:
                w.result = obj
                with self._lock:
                    if w in registry:
                        registry.remove(w)
                w.event.set()

    def _latest_state_obj(self):
        with self._lock:
            if self._state_obj is not None or self._state_bytes is None:
                return self._state_obj
            data = self._state_bytes
        try:
            st = State(state_t.decode(data))
        except Exception:  # noqa: BLE001 - a corrupt STATE is skipped
            return None
        with self._lock:
            if self._state_bytes is data:
                self._state_obj = st
        return st

    # ----------------------------------------------------------- observers
    def state(self):
        """The latest world state (State), or None before the first STATE."""
        return self._latest_state_obj()

    def state_payload(self):
        """(payload, count): the latest STATE as received (signature checked,
        trailer removed; None before the first) and how many STATEs arrived so
        far. Nothing is decoded: for readers that decode it their own way (the
        viewer reads 1,000 bodies with numpy) or only when the count moved."""
        with self._lock:
            return self._state_bytes, self._state_seq

    def contacts(self):
        """The latest contacts (Contacts, a list); empty before the first CONTACTS."""
        return Contacts(self._latest_contacts_msg())

    def contacts_payload(self):
        """(payload, count) of the latest CONTACTS, undecoded, as state_payload()."""
        with self._lock:
            return self._contacts_bytes, self._contacts_seq

    def status(self):
        """The latest STATUS (Status), or None before the first one."""
        with self._lock:
            return self._status

    def _add_callback(self, kind, callback):
        self._callbacks[kind].append(callback)

        def remove():
            if callback in self._callbacks[kind]:
                self._callbacks[kind].remove(callback)
        return remove

    def on_state(self, callback):
        """Calls callback(State) for every STATE; returns a function that removes it."""
        return self._add_callback("state", callback)

    def on_contacts(self, callback):
        """Calls callback(Contacts) for every CONTACTS; returns a remover."""
        return self._add_callback("contacts", callback)

    def on_status(self, callback):
        """Calls callback(Status) for every STATUS; returns a remover."""
        return self._add_callback("status", callback)

    def on_reply(self, callback):
        """Calls callback(reply_t) for every reply on the channel, any client's; returns a remover."""
        return self._add_callback("reply", callback)

    def on_command(self, name, msg_type, callback):
        """Calls callback(msg) on the LCM thread for every command of type
        ``msg_type`` that any client sends on the protocol channel ``name``
        (an incoming channel of protocol.toml, e.g. "RAY_CAST"), checked by
        its mac alone when the client has a key (its freshness and replay
        are the server's to judge). Returns a function that removes it. For
        observers such as the viewer, which draws every client's ray casts."""
        if name not in protocol.INCOMING:
            raise ValueError("%r is not a command channel; the commands: %s" % (name, ", ".join(protocol.INCOMING)))

        def handle(channel, data):
            data = self._auth.observe(channel, data) if self._auth else data[:unsigned_size(data)]
            try:
                msg = None if data is None else msg_type.decode(data)
            except Exception:  # noqa: BLE001 - not ours to judge
                msg = None
            if msg is not None:
                callback(msg)
        sub = self._lc.subscribe(self.channels[name], handle)
        sub.set_queue_capacity(SUBSCRIPTION_QUEUE_CAPACITY)

        def remove():
            try:
                self._lc.unsubscribe(sub)
            except Exception:  # noqa: BLE001 - already closed
                pass
        return remove

    def _wait(self, registry, predicate, timeout, what, latest):
        self._check_thread()
        w = _Waiter(predicate)
        with self._lock:
            registry.append(w)
        if predicate is not None:  # registered first, so nothing newer is missed
            current = latest()
            if current is not None and predicate(current):
                with self._lock:
                    if w in registry:
                        registry.remove(w)
                return current
        if not w.event.wait(self.timeout if timeout is None else timeout):
            with self._lock:
                if w in registry:
                    registry.remove(w)
            raise TimeoutError("no %s%s within %gs on %s%s" % (
                what, " matching the predicate" if predicate else "",
                self.timeout if timeout is None else timeout, self.url, self._auth_hint()))
        if w.error is not None:
            raise w.error
        return w.result

    def wait_for_state(self, predicate=None, timeout=None):
        """Returns the first State for which predicate(State) is true: the latest
        one if it already is, else the next one that is. Without a predicate,
        the next STATE to arrive. Raises TimeoutError after timeout s (None:
        the client's timeout)."""
        return self._wait(self._state_waiters, predicate, timeout, "STATE", self._latest_state_obj)

    def wait_for_status(self, predicate=None, timeout=None):
        """Like wait_for_state, for STATUS messages."""
        return self._wait(self._status_waiters, predicate, timeout, "STATUS", self.status)

    def wait_for_server(self, timeout=5.0):
        """Returns the latest STATUS, waiting up to timeout s for the first one."""
        return self.wait_for_status(lambda st: True, timeout=timeout)

    # ------------------------------------------------------------ commands
    def _check_thread(self):
        if threading.current_thread() is self._thread:
            raise RuntimeError("contactsim: commands and waits cannot run inside a callback")

    def _send(self, channel, msg, timeout=None, deadline=None, on_progress=None):
        """Publishes msg and waits for its reply as long as the server shows
        progress on it (PROGRESS): TimeoutError after `timeout` s of silence
        (None: the client's), or at `deadline` (time.monotonic(); None: none)."""
        self._check_thread()
        if self._stop.is_set():
            raise RuntimeError("contactsim: client is closed")
        slot = _Pending(on_progress)
        with self._lock:
            self._request_id += 1
            rid = self._request_id
            self._pending[rid] = slot
        msg.client_id = self.client_id
        msg.request_id = rid
        self._publish(self.channels[channel], msg.encode())
        timeout = self.timeout if timeout is None else timeout
        while not slot.event.is_set():
            now = time.monotonic()
            silent_until = slot.heard + timeout
            if now >= silent_until or (deadline is not None and now >= deadline):
                with self._lock:
                    mine = self._pending.pop(rid, None)
                if mine is None:  # the reply is being handed over right now
                    slot.event.wait()
                    break
                why = ("by the deadline" if deadline is not None and now >= deadline
                       else "and no progress for %gs" % timeout)
                raise TimeoutError("no reply to %s request %d %s (is the server running on %s "
                                   "with prefix %s?)%s" % (channel, rid, why, self.url, self.prefix,
                                                           self._auth_hint()))
            slot.event.wait(min(silent_until, deadline if deadline is not None else silent_until) - now)
        r = slot.reply
        if r.code != reply_t.OK:
            raise CommandError(r.message, r.code, r)
        return reply_from_msg(r)

    def _auth_hint(self):
        # the likely cause of a silence: a server with another key, or none
        if not self.auth_failures:
            return ""
        return " (%d server messages failed their signature check, the last: %s)" % (
            self.auth_failures, self.last_auth_failure)

    def _body(self, op, body_id=0):
        m = body_cmd_t()
        m.op = op
        m.body_id = int(body_id)
        return m

    def _scene(self, op):
        m = scene_cmd_t()
        m.op = op
        return m

    # bodies
    def _add(self, shape, fill, position, mass, density, orientation, velocity,
             angular_velocity, restitution, friction, fixed, kinematic, name, filt,
             center_of_mass=None, inertia=None):
        m = self._body(body_cmd_t.ADD)
        fill_filter(m, *filt)
        m.shape = shape
        fill(m)
        _mass_properties(m, center_of_mass, inertia)
        m.position = _vec(position, 3, "position")
        m.orientation = _vec(orientation, 4, "orientation")
        m.linear_velocity = _vec(velocity, 3, "velocity")
        m.angular_velocity = _vec(angular_velocity, 3, "angular_velocity")
        m.mass = 0.0 if mass is None else float(mass)
        m.density = 0.0 if density is None else float(density)
        m.fixed = bool(fixed)
        m.kinematic = bool(kinematic)
        self._material(m, restitution, friction)
        m.name = name
        return self._send("BODY_CMD", m).ids[0]

    @staticmethod
    def _material(m, restitution, friction):
        m.has_restitution = restitution is not None
        m.restitution = 0.0 if restitution is None else float(restitution)
        m.has_friction = friction is not None
        m.friction = 0.0 if friction is None else float(friction)

    def add_sphere(self, radius, *, position=(0, 0, 0), mass=None, density=None,
                   orientation=(1, 0, 0, 0), velocity=(0, 0, 0), angular_velocity=(0, 0, 0),
                   restitution=None, friction=None, fixed=False, kinematic=False, name="",
                   collision_category=None, collision_mask=None, collision_group=None):
        """Adds a sphere (radius m); returns its id. Give mass (kg) or density
        (kg/m^3), not both; neither: density 1000. fixed: a static body;
        kinematic: infinite mass, moves with its velocity (set_velocity steers
        it) and pushes dynamic bodies without being pushed (same for every add_).
        collision_category, collision_mask, collision_group: the body's
        collision filter (filters.py; None: 1, all bits, 0)."""
        def fill(m):
            m.radius = float(radius)
        return self._add(body_cmd_t.SPHERE, fill, position, mass, density, orientation, velocity,
                         angular_velocity, restitution, friction, fixed, kinematic, name,
                         (collision_category, collision_mask, collision_group))

    def add_box(self, half_extents, *, position=(0, 0, 0), mass=None, density=None,
                orientation=(1, 0, 0, 0), velocity=(0, 0, 0), angular_velocity=(0, 0, 0),
                restitution=None, friction=None, fixed=False, kinematic=False, name="",
                collision_category=None, collision_mask=None, collision_group=None):
        """Adds a box with half_extents (m, body x y z); returns its id."""
        def fill(m):
            m.half_extents = _vec(half_extents, 3, "half_extents")
        return self._add(body_cmd_t.BOX, fill, position, mass, density, orientation, velocity,
                         angular_velocity, restitution, friction, fixed, kinematic, name,
                         (collision_category, collision_mask, collision_group))

    def add_capsule(self, radius, half_length, *, position=(0, 0, 0), mass=None, density=None,
                    orientation=(1, 0, 0, 0), velocity=(0, 0, 0), angular_velocity=(0, 0, 0),
                    restitution=None, friction=None, fixed=False, kinematic=False, name="",
                    collision_category=None, collision_mask=None, collision_group=None):
        """Adds a capsule along body z (radius, half_length between cap centres, m)."""
        def fill(m):
            m.radius = float(radius)
            m.half_length = float(half_length)
        return self._add(body_cmd_t.CAPSULE, fill, position, mass, density, orientation, velocity,
                         angular_velocity, restitution, friction, fixed, kinematic, name,
                         (collision_category, collision_mask, collision_group))

    def add_convex(self, points, *, position=(0, 0, 0), mass=None, density=None,
                   orientation=(1, 0, 0, 0), velocity=(0, 0, 0), angular_velocity=(0, 0, 0),
                   restitution=None, friction=None, fixed=False, kinematic=False, name="",
                   collision_category=None, collision_mask=None, collision_group=None):
        """Adds the convex hull of points (N x 3, m, body frame); returns its id."""
        pts = np.asarray(points, dtype=np.float64)
        if pts.ndim != 2 or pts.shape[1] != 3:
            raise ValueError("points must be an N x 3 array, got shape %s" % (pts.shape,))

        def fill(m):
            m.num_points = len(pts)
            m.points = [[float(v) for v in p] for p in pts]
        return self._add(body_cmd_t.CONVEX, fill, position, mass, density, orientation, velocity,
                         angular_velocity, restitution, friction, fixed, kinematic, name,
                         (collision_category, collision_mask, collision_group))

    def add_compound(self, parts, *, position=(0, 0, 0), mass=None, density=None,
                     center_of_mass=None, inertia=None,
                     orientation=(1, 0, 0, 0), velocity=(0, 0, 0), angular_velocity=(0, 0, 0),
                     restitution=None, friction=None, fixed=False, kinematic=False, name="",
                     collision_category=None, collision_mask=None, collision_group=None):
        """Adds one rigid body of several shapes (1 to 64 parts); returns its id.

        Each part is a dict: "shape" ("sphere", "box", "capsule" or "convex")
        with that shape's "radius", "half_extents", "half_length" or "points"
        (m), and its pose in the body's frame, "position" (m) and
        "orientation" (w, x, y, z). position/orientation place that frame in
        the world; the server moves the body's origin to the centre of mass.
        Without center_of_mass (m, body frame) and inertia (kg m^2 about it,
        3 x 3 or ixx, iyy, izz, ixy, ixz, iyz; needs mass) the mass
        properties are the parts' at uniform density (docs/physics.md,
        "Compound bodies and mass properties")."""
        rows = [_part(p, k) for k, p in enumerate(parts)]

        def fill(m):
            m.num_parts = len(rows)
            m.part_shape = [r[0] for r in rows]
            m.part_radius = [r[1] for r in rows]
            m.part_half_extents = [r[2] for r in rows]
            m.part_half_length = [r[3] for r in rows]
            m.part_num_points = [len(r[4]) for r in rows]
            m.part_points = [pt for r in rows for pt in r[4]]
            m.num_part_points = len(m.part_points)
            m.part_position = [r[5] for r in rows]
            m.part_orientation = [r[6] for r in rows]
        return self._add(body_cmd_t.COMPOUND, fill, position, mass, density, orientation, velocity,
                         angular_velocity, restitution, friction, fixed, kinematic, name,
                         (collision_category, collision_mask, collision_group), center_of_mass, inertia)

    def add_plane(self, normal, offset, *, restitution=None, friction=None, name="",
                  collision_category=None, collision_mask=None, collision_group=None):
        """Adds a static plane {p : normal . p = offset}; returns its id."""
        m = self._body(body_cmd_t.ADD)
        fill_filter(m, collision_category, collision_mask, collision_group)
        m.shape = body_cmd_t.PLANE
        m.plane_normal = _vec(normal, 3, "normal")
        m.plane_offset = float(offset)
        m.orientation = [1.0, 0.0, 0.0, 0.0]
        m.fixed = True
        self._material(m, restitution, friction)
        m.name = name
        return self._send("BODY_CMD", m).ids[0]

    def remove_body(self, body_id):
        m = self._body(body_cmd_t.REMOVE, body_id)
        return self._send("BODY_CMD", m)

    def set_pose(self, body_id, position, orientation):
        """Position (m, centre of mass) and orientation (w, x, y, z)."""
        m = self._body(body_cmd_t.SET_POSE, body_id)
        m.position = _vec(position, 3, "position")
        m.orientation = _vec(orientation, 4, "orientation")
        return self._send("BODY_CMD", m)

    def set_velocity(self, body_id, linear, angular):
        """Linear (m/s, centre of mass) and angular (rad/s) velocity, world frame."""
        m = self._body(body_cmd_t.SET_VELOCITY, body_id)
        m.linear_velocity = _vec(linear, 3, "linear")
        m.angular_velocity = _vec(angular, 3, "angular")
        return self._send("BODY_CMD", m)

    def apply_force(self, body_id, force, torque=(0, 0, 0), duration=0.0):
        """Force (N, at the centre of mass) and torque (N m) for duration s of
        simulated time from the next step (0: the next step only)."""
        m = self._body(body_cmd_t.APPLY_FORCE, body_id)
        m.force = _vec(force, 3, "force")
        m.torque = _vec(torque, 3, "torque")
        m.duration = float(duration)
        return self._send("BODY_CMD", m)

    def apply_impulse(self, body_id, impulse, point=None):
        """Impulse (N s) at point (m, world), or at the centre of mass when None."""
        m = self._body(body_cmd_t.APPLY_IMPULSE, body_id)
        m.impulse = _vec(impulse, 3, "impulse")
        m.has_point = point is not None
        if point is not None:
            m.point = _vec(point, 3, "point")
        return self._send("BODY_CMD", m)

    def set_mass(self, body_id, mass=None, density=None):
        """Mass (kg) or density (kg/m^3), not both."""
        m = self._body(body_cmd_t.SET_MASS, body_id)
        m.mass = 0.0 if mass is None else float(mass)
        m.density = 0.0 if density is None else float(density)
        return self._send("BODY_CMD", m)

    def set_material(self, body_id, restitution=None, friction=None):
        """Restitution and/or friction; None leaves that one unchanged."""
        m = self._body(body_cmd_t.SET_MATERIAL, body_id)
        self._material(m, restitution, friction)
        return self._send("BODY_CMD", m)

    # world and server
    def reset(self):
        """Empties the world (time 0, default gravity and dt); method and paused state are kept."""
        return self._send("SCENE_CMD", self._scene(scene_cmd_t.RESET))

    def load_scene(self, path, *, timeout=None):
        """Loads a scene file (protobuf text), a path on the server's host."""
        m = self._scene(scene_cmd_t.LOAD_SCENE)
        m.path = os.fspath(path)
        return self._send("SCENE_CMD", m, timeout=timeout)

    def set_gravity(self, g):
        """Gravity (m/s^2, world frame)."""
        m = self._scene(scene_cmd_t.SET_GRAVITY)
        m.gravity = _vec(g, 3, "gravity")
        return self._send("SCENE_CMD", m)

    def set_timestep(self, dt):
        """Time step (s)."""
        m = self._scene(scene_cmd_t.SET_TIMESTEP)
        m.dt = float(dt)
        return self._send("SCENE_CMD", m)

    def set_contact_method(self, name, /, **params):
        """Switches the contact method; params are sent as text (floats with repr,
        bools as true/false), e.g. set_contact_method("lcp", solver="pgs", iterations=50)."""
        m = self._scene(scene_cmd_t.SET_METHOD)
        m.method = name
        m.num_params = len(params)
        m.param_names = list(params)
        m.param_values = [_param_text(v) for v in params.values()]
        return self._send("SCENE_CMD", m)

    def pause(self):
        return self._send("SCENE_CMD", self._scene(scene_cmd_t.PAUSE))

    def resume(self):
        return self._send("SCENE_CMD", self._scene(scene_cmd_t.RESUME))

    def step(self, n=1, *, timeout=None, deadline=None, progress=False):
        """Takes n steps now (the server stays paused afterwards). Returns the
        reply once the client also holds the STATE of the last step
        (``state().step == reply.step``) and on_state callbacks have seen it.

        Waits as long as the server reports progress: TimeoutError after
        `timeout` s without any (None: the client's timeout), or `deadline` s
        after the call (None: no limit). progress=True draws a tqdm bar (steps
        per second, time left); a callable gets each progress_t. A PAUSE from
        any client stops the steps: CommandError "step interrupted: cancelled
        by PAUSE ... after k of n steps"."""
        m = self._scene(scene_cmd_t.STEP)
        m.steps = int(n)
        with self._lock:
            seq0 = self._state_seq
        bar = None
        on_progress = progress if callable(progress) else None
        if progress is True:
            from tqdm.auto import tqdm
            bar = tqdm(total=int(n), unit="step", desc="step")

            def on_progress(p):
                bar.update(p.done - bar.n)
        end = None if deadline is None else time.monotonic() + deadline
        try:
            reply = self._send("SCENE_CMD", m, timeout=timeout, deadline=end, on_progress=on_progress)
            if bar is not None:
                bar.update(int(n) - bar.n)
        finally:
            if bar is not None:
                bar.close()
        wait = self.timeout if timeout is None else timeout
        with self._cond:
            ok = self._cond.wait_for(
                lambda: self._state_seq > seq0 and self._state_step >= reply.step, wait)
        if not ok:
            raise TimeoutError("STEP replied with step %d but its STATE did not arrive within %gs"
                               % (reply.step, wait))
        return reply

    def set_mode(self, mode, real_time_factor=1.0):
        """"realtime" (paced to the wall clock times real_time_factor), "free_run", or
        "lockstep" (each step waits for every registered controller's input)."""
        m = self._scene(scene_cmd_t.SET_MODE)
        if isinstance(mode, str):
            if mode.lower() not in MODES:
                raise ValueError("mode must be one of %s, got %r" % (sorted(MODES), mode))
            mode = MODES[mode.lower()]
        m.mode = int(mode)
        m.real_time_factor = float(real_time_factor)
        return self._send("SCENE_CMD", m)


__all__ = ["Client", "DEFAULT_URL", "default_url"]
