"""Robot model commands of the Client, on <prefix>_MODEL_CMD (docs/models.md).

A model is a URDF or SDF file's links and joints, added to the world as
bodies and joints in one piece and removed in one piece. ``load_model``
returns a :class:`Model` that maps the file's link and joint names to the
world's body and joint ids; ``models()`` lists every model in the world
(from <prefix>_MODEL_INFO), so a client that joins later finds them too.
"""
import os
import time

from . import model_cmd_t
from ._fields import vector
from .actuators import COORDINATE_TYPES, JointCommand
from .errors import CommandError, TimeoutError

FORMATS = {None: model_cmd_t.FORMAT_AUTO, "urdf": model_cmd_t.FORMAT_URDF, "sdf": model_cmd_t.FORMAT_SDF}


class Model:
    """One loaded model: its id, name, and its links and joints by name.

    ``links`` and ``joints`` are the file's names in the file's order.
    ``body_id(link)`` is the body that carries a link (a link welded to its
    parent by a fixed joint shares its parent's body); ``joint_id(joint)``
    is the world joint of a moving joint, 0 for a fixed (merged) or floating
    one. ``link_frame(link)`` is the link frame's (position, orientation
    (w, x, y, z)) in its body's frame.
    """

    def __init__(self, client, entry):
        self._client = client
        self.id = entry.model_id
        self.name = entry.name
        self.source = entry.source
        self.fixed_base = entry.fixed_base
        self.self_collide = entry.self_collide
        self.links = list(entry.link_names)
        self.joints = list(entry.joint_names)
        self.joint_types = dict(zip(entry.joint_names, entry.joint_types))
        self._bodies = dict(zip(entry.link_names, entry.link_bodies))
        self._joints = dict(zip(entry.joint_names, entry.joint_ids))
        self._frames = {n: (tuple(p), tuple(q)) for n, p, q in
                        zip(entry.link_names, entry.link_positions, entry.link_orientations)}
        self.joint_limits = {n: {"damping": d, "friction": f, "effort": e, "velocity": v}
                             for n, d, f, e, v in zip(entry.joint_names, entry.joint_damping,
                                                      entry.joint_friction, entry.joint_effort_limits,
                                                      entry.joint_velocity_limits)}

    def __repr__(self):
        return "Model(%d, %r, %d links, %d joints)" % (self.id, self.name, len(self.links), len(self.joints))

    def body_id(self, link):
        try:
            return self._bodies[link]
        except KeyError:
            raise KeyError("model %r has no link %r; its links: %s" % (self.name, link, self.links)) from None

    def joint_id(self, joint):
        try:
            return self._joints[joint]
        except KeyError:
            raise KeyError("model %r has no joint %r; its joints: %s" % (self.name, joint, self.joints)) from None

    def link_frame(self, link):
        self.body_id(link)  # the same error for an unknown name
        return self._frames[link]

    def link_pose(self, link, state):
        """A link frame's world pose in ``state`` (a State): (position (m),
        3x3 rotation matrix), its body's pose composed with the link's
        frame in the body: p = x + R p_off, R_link = R R_off."""
        import numpy as np  # noqa: PLC0415 - numpy only where poses are asked for
        body = state.bodies[self.body_id(link)]
        R = _rotation(body.orientation)
        p_off, q_off = self._frames[link]
        return np.asarray(body.position) + R @ np.asarray(p_off), R @ _rotation(q_off)

    def set_link_poses(self, poses):
        """Puts the model's bodies where the links' world poses say, at rest.

        poses: {link: (position (m), 3x3 rotation matrix)} for at least each
        body's first link (e.g. the forward kinematics of a joint
        configuration from pinocchio or PyBullet). A body is placed from the
        first of its links in the file's order: p_body = p_link - R_body
        p_off, R_body = R_link R_off^T, with (p_off, R_off) the link's frame
        in the body. The joints' angles are then the configuration's, since
        each hinge measures its angle from the pose at load (q = 0).
        """
        import numpy as np  # noqa: PLC0415
        done = set()
        for link in self.links:
            body = self.body_id(link)
            if body in done or link not in poses:
                continue
            done.add(body)
            p_link, R_link = (np.asarray(x, dtype=float) for x in poses[link])
            p_off, q_off = self._frames[link]
            R_body = R_link @ _rotation(q_off).T
            self._client.set_pose(body, p_link - R_body @ np.asarray(p_off), _quaternion(R_body))
            try:
                self._client.set_velocity(body, (0, 0, 0), (0, 0, 0))
            except CommandError:  # the fixed base: static, nothing to stop
                pass

    def remove(self):
        """Removes the model's bodies and joints from the world."""
        return self._client.remove_model(self.id)

    @property
    def actuated_joints(self):
        """The names of the joints with a coordinate (revolute, continuous,
        prismatic), in the file's order: the order of ``joint_state()`` and
        of the arrays the joint setters take."""
        return [n for n in self.joints if self.joint_types[n] in COORDINATE_TYPES and self._joints[n] != 0]

    def joint_state(self, timeout=None):
        """(positions, velocities, efforts): numpy arrays over
        ``actuated_joints`` from the latest STATE's joints, or JOINT_STATE's
        when newer (``Client.joint_state``; asks for a JOINT_STATE if
        neither has come yet)."""
        js = self._client.joint_state()
        if js is None:
            js = self._client.request_joint_state(timeout=timeout)
        return js.of_model(self.id)

    def joint_command(self, **fields):
        """A JointCommand over ``actuated_joints`` (for a lockstep input)."""
        return JointCommand(model=self, **fields)

    def set_joint_targets(self, positions, velocities=None, kp=None, kd=None):
        """Position control: targets (rad or m) and, when given, target rates
        and gains (numbers or one per joint); gains not given keep their
        standing values."""
        return self._client.set_joint_actuators(self.joint_command(
            target_position=positions, target_velocity=velocities, kp=kp, kd=kd))

    def set_joint_torques(self, torques):
        """Feed-forward efforts (N m or N), one per actuated joint."""
        return self._client.set_joint_actuators(self.joint_command(torque=torques))

    def set_effort_limits(self, limits):
        """The largest effort each actuator applies (N m or N, > 0; inf: none)."""
        return self._client.set_joint_actuators(self.joint_command(effort_limit=limits))

    def set_velocity_limits(self, limits):
        """The largest target rate of each actuator (rad/s or m/s, > 0; inf: none)."""
        return self._client.set_joint_actuators(self.joint_command(velocity_limit=limits))

    def clear_actuators(self):
        """Removes the actuators of every joint of the model."""
        return self._client.clear_joint_actuators(model=self)


def _rotation(wxyz):
    """The rotation matrix of a unit quaternion (w, x, y, z)."""
    import numpy as np  # noqa: PLC0415
    w, x, y, z = wxyz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _quaternion(R):
    """The unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's method)."""
    import numpy as np  # noqa: PLC0415
    t = np.trace(R)
    if t > 0:
        s = 2.0 * np.sqrt(1.0 + t)
        q = (0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s)
    else:
        i = int(np.argmax(np.diag(R)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
        v = [0.0, 0.0, 0.0]
        v[i] = 0.25 * s
        v[j] = (R[j, i] + R[i, j]) / s
        v[k] = (R[k, i] + R[i, k]) / s
        q = ((R[k, j] - R[j, k]) / s, *v)
    return tuple(float(c) for c in q)


def _command(op):
    """A model_cmd_t of op with its byte field empty (the generated default is a str)."""
    m = model_cmd_t()
    m.op = op
    m.orientation = [1.0, 0.0, 0.0, 0.0]
    m.resolved_size = 0
    m.resolved = b""
    return m


def _is_text(path_or_text):
    return path_or_text.lstrip().startswith("<")


class ModelCommands:
    """Mixin of Client: needs its ``_send(channel, msg)`` and the MODEL_INFO it keeps."""

    def load_model(self, path_or_text, *, name="", position=(0, 0, 0), orientation=(1, 0, 0, 0),
                   fixed_base=False, self_collide=False, max_hull_vertices=0, format=None, timeout=None):
        """Loads a URDF or SDF model and returns its :class:`Model`.

        path_or_text: a file path (a file on this host is sent as its absolute
        path, anything else as given, for the server to find among its model
        paths) or the file's text (it starts with "<"). name: the model's name
        in the world (unique; "" = the file's). position (m) and orientation
        (w, x, y, z): the root link's frame in the world. fixed_base: the root
        link is static. self_collide: the model's links collide with each
        other (two joined by a joint never do). max_hull_vertices: each
        collision mesh becomes the convex hull of at most this many of its
        vertices (>= 4; 0: the server's default, 64; -1: every vertex, the
        full hull; docs/models.md, "Hull vertex budget"). format: "urdf", "sdf" or None
        (from the extension or the text). Bad input raises CommandError with
        the server's message, and nothing is added.
        """
        if format not in FORMATS:
            raise ValueError("format must be 'urdf', 'sdf' or None, got %r" % (format,))
        m = _command(model_cmd_t.LOAD)
        m.format = FORMATS[format]
        if _is_text(path_or_text):
            m.text = path_or_text
        else:
            m.path = os.path.abspath(path_or_text) if os.path.exists(path_or_text) else path_or_text
        m.name = name
        m.position = vector(position, 3, "position")
        m.orientation = vector(orientation, 4, "orientation")
        m.fixed_base = bool(fixed_base)
        m.self_collide = bool(self_collide)
        m.max_hull_vertices = int(max_hull_vertices)
        reply = self._send("MODEL_CMD", m, timeout=timeout)
        return self._model_with_id(reply.ids[0], timeout)

    def remove_model(self, model_id):
        """Removes a model (its id, or a Model) with its bodies and joints."""
        m = _command(model_cmd_t.REMOVE)
        m.model_id = int(getattr(model_id, "id", model_id))
        return self._send("MODEL_CMD", m)

    def models(self, timeout=None):
        """Every model in the world, {name: Model}, as MODEL_INFO lists them now."""
        info = self._request_model_info(timeout)
        return {e.name: Model(self, e) for e in info.models}

    def model(self, name, timeout=None):
        """The loaded model called ``name``; KeyError if there is none."""
        found = self.models(timeout)
        if name not in found:
            raise KeyError("no model named %r; loaded: %s" % (name, sorted(found)))
        return found[name]

    def _request_model_info(self, timeout):
        m = _command(model_cmd_t.INFO)
        seq = self._model_info_seq
        self._send("MODEL_CMD", m, timeout=timeout)
        return self._wait_model_info(lambda info: self._model_info_seq > seq, timeout)

    def _model_with_id(self, model_id, timeout):
        def has(info):
            return any(e.model_id == model_id for e in info.models)
        try:
            info = self._wait_model_info(has, 0.5)
        except TimeoutError:  # MODEL_INFO lost, or this client joined after it: ask for it
            info = self._request_model_info(timeout)
        for e in info.models:
            if e.model_id == model_id:
                return Model(self, e)
        raise TimeoutError("model %d is not in MODEL_INFO" % model_id)

    def _wait_model_info(self, predicate, timeout):
        timeout = self.timeout if timeout is None else timeout
        deadline = time.monotonic() + timeout
        with self._cond:
            while self._model_info is None or not predicate(self._model_info):
                left = deadline - time.monotonic()
                if left <= 0:
                    raise TimeoutError("no MODEL_INFO within %gs" % timeout)
                self._cond.wait(left)
            return self._model_info
