"""Joint commands of the Client, on <prefix>_JOINT_CMD (docs/protocol.md).

A joint holds two bodies together, or a body to the world (``body_b=None``):
"distance" (a rod: body_a's centre of mass at ``length`` from the anchor on
body_b), "ball" (ball and socket at the anchor), "hinge" (a ball that turns
only about ``axis``, optionally within ``limits`` = (lower, upper) rad of the
pose at creation), "fixed" (a weld) and "prismatic" (a slider: body_b keeps
its orientation and slides along ``axis``, optionally within ``limits`` =
(lower, upper) m of the pose at creation). Hinges and sliders take
``damping`` (N m s/rad or N s/m) and Coulomb ``friction`` (N m or N); their
limits are one-sided stops. The anchor and axis are world
coordinates at the moment of creation; the server keeps them in the bodies'
frames afterwards. Bad input raises CommandError with the server's message,
and the world is left as it was.
"""
from . import joint_cmd_t
from ._fields import vector

KINDS = {
    "distance": joint_cmd_t.DISTANCE,
    "ball": joint_cmd_t.BALL,
    "hinge": joint_cmd_t.HINGE,
    "fixed": joint_cmd_t.FIXED,
    "prismatic": joint_cmd_t.PRISMATIC,
}


class JointCommands:
    """Mixin of Client: needs its ``_send(channel, msg)``."""

    def add_joint(self, kind, body_a, body_b, *, anchor, axis=None, length=None, limits=None, damping=None,
                  friction=None, collide_connected=False):
        """Adds a joint and returns its id (ids count from 1, never reused).

        kind: "distance", "ball", "hinge", "fixed" or "prismatic". body_b
        None: the world. anchor (m, world): the joint point (distance: the
        point on body_b). axis (world): hinge and prismatic, required there.
        length (m): distance only; None = the current distance. limits:
        hinge (rad) and prismatic (m), (lower, upper). damping (N m s/rad or
        N s/m) and friction (N m or N): hinge and prismatic, >= 0.
        collide_connected: may body_a and body_b touch each other (False, the
        default, as in PyBullet and Drake: never).
        """
        if kind not in KINDS:
            raise ValueError("kind must be one of %s, got %r" % (sorted(KINDS), kind))
        m = joint_cmd_t()
        m.op = joint_cmd_t.ADD
        m.kind = KINDS[kind]
        m.body_a = int(body_a)
        m.body_b = 0 if body_b is None else int(body_b)
        m.anchor = vector(anchor, 3, "anchor")
        m.has_axis = axis is not None
        m.axis = vector(axis, 3, "axis") if axis is not None else [0.0, 0.0, 0.0]
        m.has_length = length is not None
        m.length = 0.0 if length is None else float(length)
        m.has_limits = limits is not None
        m.lower, m.upper = (0.0, 0.0) if limits is None else vector(limits, 2, "limits")
        m.has_damping = damping is not None
        m.damping = 0.0 if damping is None else float(damping)
        m.has_friction = friction is not None
        m.friction = 0.0 if friction is None else float(friction)
        if not isinstance(collide_connected, bool):
            raise TypeError("collide_connected must be True or False, got %r" % (collide_connected,))
        m.collide_connected = collide_connected
        return self._send("JOINT_CMD", m).ids[0]

    def remove_joint(self, joint_id):
        """Removes a joint; the bodies stay and move freely again."""
        m = joint_cmd_t()
        m.op = joint_cmd_t.REMOVE
        m.joint_id = int(joint_id)
        return self._send("JOINT_CMD", m)
