"""The wire fields of an ADD that more than one shape shares: a compound's
parts and an explicit centre of mass and inertia (docs/protocol.md,
BODY_CMD)."""
import numpy as np

from . import body_cmd_t
from ._fields import vector as _vec


_PART_SHAPES = {"sphere": body_cmd_t.SPHERE, "box": body_cmd_t.BOX,
                "capsule": body_cmd_t.CAPSULE, "convex": body_cmd_t.CONVEX}


def part(part, k):
    """One compound part as its wire fields: (shape, radius, half_extents,
    half_length, points, position, orientation)."""
    shape = part.get("shape")
    if shape not in _PART_SHAPES:
        raise ValueError("parts[%d].shape must be one of %s, got %r" % (k, ", ".join(_PART_SHAPES), shape))
    points = np.asarray(part.get("points", np.zeros((0, 3))), dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError("parts[%d].points must be an N x 3 array, got shape %s" % (k, points.shape))
    return (_PART_SHAPES[shape], float(part.get("radius", 0.0)),
            _vec(part.get("half_extents", (0, 0, 0)), 3, "parts[%d].half_extents" % k),
            float(part.get("half_length", 0.0)), [[float(v) for v in p] for p in points],
            _vec(part.get("position", (0, 0, 0)), 3, "parts[%d].position" % k),
            _vec(part.get("orientation", (1, 0, 0, 0)), 4, "parts[%d].orientation" % k))


def mass_properties(m, center_of_mass, inertia):
    """Explicit centre of mass (m, body frame) and inertia (kg m^2: 3 x 3, or
    ixx, iyy, izz, ixy, ixz, iyz) on an ADD."""
    m.has_center_of_mass = center_of_mass is not None
    if center_of_mass is not None:
        m.center_of_mass = _vec(center_of_mass, 3, "center_of_mass")
    m.has_inertia = inertia is not None
    if inertia is not None:
        a = np.asarray(inertia, dtype=np.float64)
        if a.shape == (3, 3):
            a = np.array([a[0, 0], a[1, 1], a[2, 2], a[0, 1], a[0, 2], a[1, 2]])
        m.inertia = _vec(a, 6, "inertia")
