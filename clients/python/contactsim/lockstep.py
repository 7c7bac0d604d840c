"""Lockstep co-simulation from Python (docs/lockstep.md).

``Client`` inherits ``LockstepCommands``: ``register_controller()``,
``send_input(step, forces, joints)`` and ``release_controller()``.
``Controller`` runs a callback state -> forces in lockstep: each STATE k-1
is answered with the input for step k from the client's receive thread, so
a step costs one STATE and one input on the wire. An input's ``joints`` (a
JointCommand) set joints' actuator fields for that one step only.
"""
import threading

from . import input_t, joint_state_t, scene_cmd_t
from .actuators import JointCommand, JointState, encode_joint_command
from .errors import TimeoutError

LATE_POLICIES = {None: scene_cmd_t.LATE_DEFAULT, "wait": scene_cmd_t.LATE_WAIT,
                 "reuse": scene_cmd_t.LATE_REUSE, "drop": scene_cmd_t.LATE_DROP}


def _wrench(value):
    """force, or (force, torque) -> two 3-tuples of floats."""
    if len(value) == 2 and all(hasattr(v, "__len__") for v in value):
        force, torque = value
    else:
        force, torque = value, (0.0, 0.0, 0.0)
    return [float(x) for x in force], [float(x) for x in torque]


class LockstepCommands:
    def register_controller(self, late=None, timeout=None):
        """Makes this client a lockstep controller: in lockstep mode the server
        takes no step before this client's input for it. ``late``: "wait",
        "reuse" (its last input, after ``timeout`` s) or "drop" (released
        after ``timeout`` s); None: the server's configured policy."""
        if late not in LATE_POLICIES:
            raise ValueError("late must be one of wait, reuse, drop or None, got %r" % (late,))
        m = self._scene(scene_cmd_t.REGISTER_CONTROLLER)
        m.late_policy = LATE_POLICIES[late]
        m.late_timeout = float(timeout or 0.0)
        return self._send("SCENE_CMD", m)

    def release_controller(self):
        return self._send("SCENE_CMD", self._scene(scene_cmd_t.RELEASE_CONTROLLER))

    def send_input(self, step, forces=None, joints=None):
        """Publishes this controller's input for ``step`` (the last STATE's
        step + 1): ``forces`` maps body id -> force (N, world) or
        (force, torque); None or {} means no input. ``joints``: a
        JointCommand acting for this step only (the joints' standing
        settings return after it). Returns at once: the STATE of ``step``
        acknowledges it; a refused input gets an error reply (see on_reply)
        and the server does not take the step until a good input comes.
        Safe to call from an on_state callback."""
        request_id, payload = self._encode_input(step, forces, joints)
        self._publish_input(payload)
        return request_id

    def _encode_input(self, step, forces, joints=None):
        """-> (request id, encoded input_t); a resend reuses both."""
        m = input_t()
        m.client_id = self.client_id
        with self._lock:
            self._request_id += 1
            m.request_id = self._request_id
        m.step = int(step)
        for body, value in sorted((forces or {}).items()):
            f, t = _wrench(value)
            m.body_ids.append(int(body))
            m.forces.append(f)
            m.torques.append(t)
        m.num_bodies = len(m.body_ids)
        m.joints = encode_joint_command(joints)
        return m.request_id, m.encode()

    def _publish_input(self, payload):
        self._publish(self.channels["INPUT"], payload)


def _split(output):
    """A callback's answer -> (forces, JointCommand or None)."""
    if isinstance(output, JointCommand):
        return None, output
    if isinstance(output, tuple) and len(output) == 2 and isinstance(output[1], JointCommand):
        return output
    return output, None


class Controller:
    """Runs ``callback(state) -> forces`` in lockstep (forces as in
    ``send_input``). The callback may also return a JointCommand, or
    (forces, JointCommand). With ``joint_state=True`` it is called as
    ``callback(state, joint_state)`` with the joints STATE carries (a
    JointState named from MODEL_INFO; empty when the world has none), so a
    step needs one message. Use as a context manager or call
    start() / stop()::

        with Controller(client, pd) as ctl:
            client.set_mode("lockstep"); client.resume()
            ctl.wait_for_step(720)
    """

    def __init__(self, client, callback, late=None, timeout=None, joint_state=False):
        self.client = client
        self.callback = callback
        self.joint_state = joint_state
        self.late = late
        self.timeout = timeout
        self.answered = -1          # step of the last STATE answered
        self.error = None           # an exception raised by the callback
        self._cond = threading.Condition()
        self._remove = None
        self._registered = False
        self._last_payload = None   # the input that answered `answered`

    def _on_state(self, state):
        # A STATE before the registration is acknowledged is not answered: its
        # input could reach the server first and be refused. The server sends
        # STATE again while it waits, so nothing is missed.
        if not self._registered or self.error is not None or state.step < self.answered:
            return
        if state.step == self.answered:
            # published again because the server still waits: our input was
            # lost (UDP) or refused; resend it unchanged (same request id, so
            # a duplicate of an input already applied is ignored)
            self.client._publish_input(self._last_payload)
            return
        js = None
        if self.joint_state:
            js = self.client.joints_of(state)
            if js is None:
                js = JointState(joint_state_t())
                js.step, js.time = state.step, state.time
        try:
            out = self.callback(state, js) if self.joint_state else self.callback(state)
            forces, joints = _split(out)
        except Exception as e:  # surfaced by wait_for_step
            self.error = e
            forces, joints = None, None
        _, self._last_payload = self.client._encode_input(state.step + 1, forces, joints)
        self.client._publish_input(self._last_payload)
        with self._cond:
            self.answered = state.step
            self._cond.notify_all()

    def start(self):
        self._remove = self.client.on_state(self._on_state)
        reply = self.client.register_controller(self.late, self.timeout)
        self._registered = True
        return reply

    def stop(self):
        self._registered = False
        if self._remove is not None:
            self._remove()
            self._remove = None
        return self.client.release_controller()

    def wait_for_step(self, step, timeout=30.0):
        """Blocks until the STATE of ``step`` was answered; raises the
        callback's exception, or TimeoutError."""
        with self._cond:
            ok = self._cond.wait_for(lambda: self.answered >= step or self.error is not None, timeout)
        if self.error is not None:
            raise self.error
        if not ok:
            raise TimeoutError("lockstep reached step %d, not %d, within %gs" % (self.answered, step, timeout))

    def __enter__(self):
        self.start()
        return self

    def __exit__(self, *exc):
        self.stop()
