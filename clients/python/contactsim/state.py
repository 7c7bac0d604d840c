"""Friendly, numpy-based views of the STATE, CONTACTS, STATUS and REPLY messages."""
from collections import namedtuple

import numpy as np

from . import status_t
from .actuators import JointState

# The run modes by their wire value, the Python client's one table of them
# (client.MODES and logread read it). The names are the server's
# (kRunModeNames, service/server/command.h); tests/python/test_mode_names.py
# holds the three tables of the project to one another.
MODE_NAMES = {status_t.REALTIME: "realtime", status_t.FREE_RUN: "free_run", status_t.LOCKSTEP: "lockstep"}
VALUE_KINDS = {1: "impulse", 2: "force"}


def _arr(values):
    return np.array(values, dtype=np.float64)


class BodyState:
    """One body: ``id``; numpy ``position`` (m), ``orientation`` (w, x, y, z),
    ``linear_velocity`` (m/s) and ``angular_velocity`` (rad/s), world frame."""

    __slots__ = ("id", "position", "orientation", "linear_velocity", "angular_velocity")

    def __init__(self, msg):
        self.id = msg.id
        self.position = _arr(msg.position)
        self.orientation = _arr(msg.orientation)
        self.linear_velocity = _arr(msg.linear_velocity)
        self.angular_velocity = _arr(msg.angular_velocity)

    def __eq__(self, other):
        if not isinstance(other, BodyState):
            return NotImplemented
        return self.id == other.id and all(
            np.array_equal(getattr(self, f), getattr(other, f)) for f in self.__slots__[1:])

    def __repr__(self):
        return "BodyState(id=%d, position=%s, orientation=%s, linear_velocity=%s, angular_velocity=%s)" % (
            self.id, self.position, self.orientation, self.linear_velocity, self.angular_velocity)


class State:
    """The world after a step: ``time`` (s), ``step``, ``state_hash``,
    ``input_digest`` (of the lockstep inputs applied in the step, 0 if none),
    ``kinetic_energy`` and ``potential_energy`` (J, of the dynamic bodies) and
    ``bodies``, a dict body id -> BodyState in ascending id order, and
    ``joints``, the joints with a coordinate as a JointState (named by id;
    ``Client.joints_of`` names them from MODEL_INFO), None when the world has
    none. Two states compare equal when every field of every body is
    bit-identical."""

    __slots__ = ("time", "step", "state_hash", "input_digest", "kinetic_energy", "potential_energy", "bodies",
                 "joints", "raw")

    def __init__(self, msg):
        self.time = msg.time
        self.step = msg.step
        self.state_hash = msg.state_hash
        self.input_digest = msg.input_digest
        self.kinetic_energy = msg.kinetic_energy
        self.potential_energy = msg.potential_energy
        self.bodies = {b.id: BodyState(b) for b in msg.bodies}
        self.joints = JointState.from_state(msg) if msg.num_joints > 0 else None
        self.raw = msg

    def __eq__(self, other):
        if not isinstance(other, State):
            return NotImplemented
        return (self.time == other.time and self.step == other.step
                and self.state_hash == other.state_hash and self.bodies == other.bodies)

    def __repr__(self):
        return "State(time=%g, step=%d, state_hash=%#x, %d bodies)" % (
            self.time, self.step, self.state_hash & 0xFFFFFFFFFFFFFFFF, len(self.bodies))


class Contact:
    """One contact point: ``body_a``, ``body_b``, numpy ``point`` (m) and
    ``normal`` (unit, from a to b), ``depth`` (m, > 0 overlapping),
    ``normal_value`` and numpy ``tangent_value`` (N s or N, see Contacts.value_kind)."""

    __slots__ = ("body_a", "body_b", "point", "normal", "depth", "normal_value", "tangent_value")

    def __init__(self, msg):
        self.body_a = msg.body_a
        self.body_b = msg.body_b
        self.point = _arr(msg.point)
        self.normal = _arr(msg.normal)
        self.depth = msg.depth
        self.normal_value = msg.normal_value
        self.tangent_value = _arr(msg.tangent_value)

    def __repr__(self):
        return "Contact(%d-%d, point=%s, normal=%s, depth=%g, normal_value=%g)" % (
            self.body_a, self.body_b, self.point, self.normal, self.depth, self.normal_value)


class Contacts(list):
    """The contacts of a step: a list of Contact with ``time``, ``step``,
    ``method`` (contact method name) and ``value_kind`` ("impulse" or "force")."""

    def __init__(self, msg=None):
        super().__init__(Contact(c) for c in (msg.contacts if msg is not None else ()))
        self.time = msg.time if msg is not None else 0.0
        self.step = msg.step if msg is not None else -1
        self.method = msg.method if msg is not None else ""
        self.value_kind = VALUE_KINDS.get(msg.value_kind, str(msg.value_kind)) if msg is not None else ""
        self.raw = msg


class Status:
    """The server's heartbeat. Every status_t field is an attribute with the
    same name; ``mode`` is "realtime", "free_run" or "lockstep". ``as_dict()`` gives a dict."""

    def __init__(self, msg):
        # the generated type lists its fields once; take them from there
        self.FIELDS = tuple(type(msg).__slots__)
        for f in self.FIELDS:
            setattr(self, f, getattr(msg, f))
        self.mode = MODE_NAMES.get(msg.mode, str(msg.mode))
        self.raw = msg

    def as_dict(self):
        return {f: getattr(self, f) for f in self.FIELDS}

    def contract(self):
        """What the active contact method simulates (docs/physics.md, "Method
        contract"), from ``method_contract``: {"joints": bool, "restitution":
        bool, "kinematic": bool, "friction": "coulomb disk", ...}."""
        out = {}
        for part in self.method_contract.split("; ") if self.method_contract else ():
            key, _, value = part.partition("=")
            out[key] = {"yes": True, "no": False}.get(value, value)
        return out

    def __getitem__(self, key):
        if key not in self.FIELDS:
            raise KeyError(key)
        return getattr(self, key)

    def __repr__(self):
        return "Status(%s)" % ", ".join("%s=%r" % (f, getattr(self, f)) for f in self.FIELDS)


Reply = namedtuple("Reply", "code message step time ids")
Reply.__doc__ = """A successful reply: ``code`` (0), ``message``, ``step`` and ``time``
at which the command took effect, ``ids`` (new body ids for ADD)."""


def reply_from_msg(msg):
    return Reply(msg.code, msg.message, msg.step, msg.time, tuple(msg.ids))
