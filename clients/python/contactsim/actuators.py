"""Joint actuators and joint state of the Client (docs/actuators.md, "Joint
channels").

A hinge or prismatic joint takes an actuator: a feed-forward ``torque``, PD
targets (``target_position`` with ``kp``, ``target_velocity`` with ``kd``)
and ``effort_limit`` / ``velocity_limit``. ``set_joint_actuator`` and
``set_joint_actuators`` change the standing settings on
<prefix>_ACTUATOR_CMD; only the fields given change, so new targets keep the
gains. A lockstep input carries a :class:`JointCommand` for one step.
STATE carries every joint's coordinate, rate and effort (its joint block,
``State.joints``), and <prefix>_JOINT_STATE the same with the joints' names
beside STATE outside lockstep (the server's ``joint_state`` option);
``joint_state()`` is the latest of the two as a :class:`JointState`.
"""
import threading

import numpy as np

from . import actuator_cmd_t, joint_command_t, joint_state_t
from .errors import TimeoutError

# field name -> (bit of joint_command_t.fields, column of joint_command_t)
FIELDS = {
    "torque": (joint_command_t.TORQUE, "torques"),
    "target_position": (joint_command_t.TARGET_POSITION, "target_positions"),
    "target_velocity": (joint_command_t.TARGET_VELOCITY, "target_velocities"),
    "kp": (joint_command_t.KP, "kp"),
    "kd": (joint_command_t.KD, "kd"),
    "effort_limit": (joint_command_t.EFFORT_LIMIT, "effort_limits"),
    "velocity_limit": (joint_command_t.VELOCITY_LIMIT, "velocity_limits"),
}
COORDINATE_TYPES = ("revolute", "continuous", "prismatic")


class JointCommand:
    """Actuator fields for a list of joints: ``joints`` (world joint ids) or
    ``model`` (a Model or its id; with ``joints`` None, every joint of the
    model with a coordinate, in ``Model.actuated_joints`` order). Each field
    is a number (the same for every joint) or one value per joint; a field
    left None is not sent, so the joint keeps its standing value."""

    def __init__(self, joints=None, *, model=None, **fields):
        unknown = set(fields) - set(FIELDS)
        if unknown:
            raise TypeError("unknown actuator fields %s; known: %s" % (sorted(unknown), list(FIELDS)))
        self.model = int(getattr(model, "id", model) or 0)
        self.joints = [] if joints is None else [int(j) for j in np.atleast_1d(joints)]
        if self.model == 0 and not self.joints:
            raise ValueError("give joints (world joint ids) or a model")
        given = {k: v for k, v in fields.items() if v is not None}
        n = len(self.joints)
        if not n:
            sizes = {np.size(v) for v in given.values() if np.ndim(v) > 0}
            if len(sizes) > 1:
                raise ValueError("the fields have different lengths %s" % sorted(sizes))
            n = sizes.pop() if sizes else len(getattr(model, "actuated_joints", ()))
        self.count = n
        self.fields = {}
        for k, v in given.items():
            a = np.broadcast_to(np.asarray(v, dtype=np.float64), (n,)) if np.ndim(v) == 0 else \
                np.asarray(v, dtype=np.float64)
            if a.shape != (n,):
                raise ValueError("%s must have %d values, got shape %s" % (k, n, a.shape))
            self.fields[k] = a

    def message(self):
        """The joint_command_t."""
        return encode_joint_command(self)


def encode_joint_command(cmd):
    """A joint_command_t of a JointCommand, or an empty one for None."""
    m = joint_command_t()
    for _, column in FIELDS.values():
        setattr(m, column, [])
    if cmd is None:
        return m
    m.model_id = cmd.model
    m.joint_ids = list(cmd.joints)
    m.num_ids = len(m.joint_ids)
    m.num_joints = cmd.count
    for name, (bit, column) in FIELDS.items():
        values = cmd.fields.get(name)
        if values is not None:
            m.fields |= bit
        setattr(m, column, [0.0] * cmd.count if values is None else [float(x) for x in values])
    return m


class JointState:
    """One JOINT_STATE: ``joint_ids``, ``model_ids`` (int64 arrays),
    ``names`` (list), ``positions`` (rad or m), ``velocities`` (rad/s or
    m/s), ``efforts`` (N m or N, the actuator's effort in the last step) as
    numpy arrays, grouped by model in each model's joint order."""

    def __init__(self, msg):
        self.step = msg.step
        self.time = msg.time
        self.joint_ids = np.array(msg.joint_ids, dtype=np.int64)
        self.model_ids = np.array(msg.model_ids, dtype=np.int64)
        self.names = list(msg.names)
        self.positions = np.array(msg.positions, dtype=np.float64)
        self.velocities = np.array(msg.velocities, dtype=np.float64)
        self.efforts = np.array(msg.efforts, dtype=np.float64)

    @classmethod
    def from_state(cls, msg, names=None):
        """The joint block of a state_t: the same joints in the same order
        as the JOINT_STATE of its step. ``names`` maps joint id -> the model
        file's name (MODEL_INFO's); a joint it lacks is named by its id in
        decimal, as JOINT_STATE names a joint of no model."""
        js = cls.__new__(cls)
        js.step = msg.step
        js.time = msg.time
        js.joint_ids = np.array(msg.joint_ids, dtype=np.int64)
        js.model_ids = np.array(msg.joint_model_ids, dtype=np.int64)
        names = names or {}
        js.names = [names.get(int(j), str(int(j))) for j in msg.joint_ids]
        js.positions = np.array(msg.joint_positions, dtype=np.float64)
        js.velocities = np.array(msg.joint_velocities, dtype=np.float64)
        js.efforts = np.array(msg.joint_efforts, dtype=np.float64)
        return js

    def of_model(self, model_id):
        """(positions, velocities, efforts) of one model's joints, in its order."""
        sel = self.model_ids == int(model_id)
        return self.positions[sel], self.velocities[sel], self.efforts[sel]

    def of_joints(self, joint_ids):
        """(positions, velocities, efforts) of the given joints, in that order."""
        index = {int(j): i for i, j in enumerate(self.joint_ids)}
        try:
            sel = [index[int(j)] for j in joint_ids]
        except KeyError as e:
            raise KeyError("joint %s has no coordinate in JOINT_STATE" % e.args[0]) from None
        return self.positions[sel], self.velocities[sel], self.efforts[sel]

    def __iter__(self):  # positions, velocities, efforts = sim.joint_state()
        return iter((self.positions, self.velocities, self.efforts))


class ActuatorCommands:
    """Mixin of Client: needs its ``_send``, ``_lock`` and ``_callbacks``."""

    def _init_actuators(self):
        self._joint_state = None
        self._joint_state_seq = 0
        self._joint_state_cond = threading.Condition(self._lock)
        self._callbacks["joint_state"] = []
        return [self._lc.subscribe(self.channels["JOINT_STATE"], self._on_joint_state_msg)]

    def _on_joint_state_msg(self, channel, data):
        msg = self._decode(channel, data, joint_state_t)
        if msg is None:
            return
        js = JointState(msg)
        with self._joint_state_cond:
            self._joint_state = js
            self._joint_state_seq += 1
            self._joint_state_cond.notify_all()
        self._call("joint_state", js)

    def set_joint_actuator(self, joint_id, **fields):
        """Sets the fields given (torque, target_position, target_velocity,
        kp, kd, effort_limit, velocity_limit) of one joint's standing
        actuator; the others keep their values."""
        return self.set_joint_actuators(JointCommand([joint_id], **fields))

    def set_joint_actuators(self, command=None, **kwargs):
        """Sets standing actuator fields of many joints at once: a
        JointCommand, or its arguments (joints=..., model=..., fields). The
        whole command is refused (CommandError) if any joint or value is."""
        cmd = command if command is not None else JointCommand(**kwargs)
        m = actuator_cmd_t()
        m.op = actuator_cmd_t.SET
        m.joints = encode_joint_command(cmd)
        return self._send("ACTUATOR_CMD", m)

    def clear_joint_actuators(self, joints=None, *, model=None):
        """Removes the actuators of the joints (ids) or of a model's joints."""
        cmd = JointCommand(joints, model=model)
        m = actuator_cmd_t()
        m.op = actuator_cmd_t.CLEAR
        m.joints = encode_joint_command(cmd)
        m.joints.num_joints = len(cmd.joints)
        m.joints.fields = 0
        for _, column in FIELDS.values():
            setattr(m.joints, column, [0.0] * len(cmd.joints))
        return self._send("ACTUATOR_CMD", m)

    def request_joint_state(self, timeout=None):
        """Asks the server for a JOINT_STATE now (it publishes one with each
        STATE; a paused server publishes none) and returns it."""
        m = actuator_cmd_t()
        m.op = actuator_cmd_t.STATE
        m.joints = encode_joint_command(None)
        with self._lock:
            seq = self._joint_state_seq
        reply = self._send("ACTUATOR_CMD", m, timeout=timeout)
        timeout = self.timeout if timeout is None else timeout
        with self._joint_state_cond:
            if not self._joint_state_cond.wait_for(
                    lambda: self._joint_state_seq > seq and self._joint_state.step >= reply.step, timeout=timeout):
                raise TimeoutError("no JOINT_STATE within %gs of the request" % timeout)
            return self._joint_state

    def joint_state(self):
        """The latest joint state as a JointState: the joint block of the
        latest STATE, or the latest JOINT_STATE when that is of the same
        step (it names the joints without MODEL_INFO) or newer, or STATE
        carries no joints; None before either."""
        with self._lock:
            js = self._joint_state
        st = self._latest_state_obj()
        if st is None or st.joints is None or (js is not None and js.step >= st.step):
            return js
        return self.joints_of(st)

    def joints_of(self, state):
        """A State's joint block as a JointState named from MODEL_INFO (see
        JointState.from_state), or None when the STATE carries no joints."""
        if state.joints is None:
            return None
        names = self._joint_names()
        if names:
            return JointState.from_state(state.raw, names)
        return state.joints

    def _joint_names(self):
        # joint id -> name from the latest MODEL_INFO, rebuilt when it changes
        with self._lock:
            info = getattr(self, "_model_info", None)
            cached = getattr(self, "_joint_names_cache", (None, {}))
        if info is None:
            return {}
        if cached[0] is not info:
            names = {int(j): n for e in info.models for n, j in zip(e.joint_names, e.joint_ids) if j != 0}
            cached = (info, names)
            with self._lock:
                self._joint_names_cache = cached
        return cached[1]

    def wait_for_joint_state(self, predicate=None, timeout=None):
        """Waits for a JOINT_STATE after this call (satisfying predicate,
        when given) and returns it."""
        self._check_thread()
        timeout = self.timeout if timeout is None else timeout
        with self._joint_state_cond:
            seq = self._joint_state_seq

            def ready():
                return self._joint_state_seq > seq and (predicate is None or predicate(self._joint_state))
            if not self._joint_state_cond.wait_for(ready, timeout=timeout):
                raise TimeoutError("no JOINT_STATE within %gs" % timeout)
            return self._joint_state

    def on_joint_state(self, callback):
        """Calls callback(JointState) with each one; returns a remover."""
        return self._add_callback("joint_state", callback)
