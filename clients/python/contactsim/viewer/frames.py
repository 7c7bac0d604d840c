"""The binary WebSocket frames the page draws from (docs/viewer.md).

Each is a little-endian Float64Array whose first value names it, so the page
reads a 1,000-body pose frame without parsing text:

* POSES:    [1, step, time, kinetic J, potential J, n, then per body id, px, py, pz, qw, qx, qy, qz]
* CONTACTS: [2, step, n, then per contact px, py, pz, nx, ny, nz]
* RAYS:     [3, step, kind (0 ray cast, 1 range sensors), n, then per ray body, ox, oy, oz, ex, ey, ez, hit,
            nx, ny, nz]

Doubles keep the positions exact: the page shows what STATE says.
"""
import numpy as np

from .. import contacts_t, state_t

# state_t on the wire (lcmtypes/state_t.lcm): fingerprint, time, step,
# state_hash, input_digest, kinetic and potential energy, num_bodies, then
# each body_state_t (nested: no fingerprint) as id and 13 doubles, then the
# joint block: num_joints and five columns of that many 8-byte values
# (ids, model ids, positions, velocities, efforts), big-endian
_STATE_HEAD = np.dtype([("fp", "V8"), ("time", ">f8"), ("step", ">i8"), ("hash", ">i8"), ("digest", ">i8"),
                        ("kinetic", ">f8"), ("potential", ">f8"), ("n", ">i4")])
_BODY = np.dtype([("id", ">i8"), ("x", ">f8", 3), ("q", ">f8", 4), ("v", ">f8", 3), ("w", ">f8", 3)])
_JOINT_COLUMNS = 5
_STATE_FP = state_t._get_packed_fingerprint()
# contacts_t: fingerprint, time, step, method (int32 length with its NUL, bytes),
# value_kind (int8), num_contacts, then each contact_t
_CONTACT = np.dtype([("a", ">i8"), ("b", ">i8"), ("point", ">f8", 3), ("normal", ">f8", 3), ("depth", ">f8"),
                     ("value", ">f8"), ("tangent", ">f8", 3)])
_CONTACTS_FP = contacts_t._get_packed_fingerprint()

POSES, CONTACTS = 1.0, 2.0
POSE_WIDTH = 8       # id, position (3), orientation w x y z (4)
CONTACT_WIDTH = 6    # point (3), normal (3)


def poses_frame(step, time, kinetic, potential, ids, positions, orientations):
    """ids (n,), positions (n, 3) m, orientations (n, 4) w x y z -> bytes."""
    ids = np.asarray(ids, dtype=np.float64).reshape(-1, 1)
    rows = np.hstack([ids, np.asarray(positions, np.float64).reshape(-1, 3),
                      np.asarray(orientations, np.float64).reshape(-1, 4)])
    head = np.array([POSES, step, time, kinetic, potential, len(ids)], dtype=np.float64)
    return head.astype("<f8").tobytes() + rows.astype("<f8").tobytes()


def read_state(payload):
    """(head, bodies) numpy records of a STATE payload, without one Python
    object per body; None when it is not exactly one state_t of this layout."""
    if len(payload) < _STATE_HEAD.itemsize or payload[:8] != _STATE_FP:
        return None
    head = np.frombuffer(payload, _STATE_HEAD, count=1)[0]
    n = int(head["n"])
    joints_at = _STATE_HEAD.itemsize + n * _BODY.itemsize
    if n < 0 or len(payload) < joints_at + 4:
        return None
    joints = int(np.frombuffer(payload, ">i4", count=1, offset=joints_at)[0])
    if joints < 0 or len(payload) != joints_at + 4 + joints * _JOINT_COLUMNS * 8:
        return None
    return head, np.frombuffer(payload, _BODY, count=n, offset=_STATE_HEAD.itemsize)


def poses_from_records(head, bodies):
    """A POSES frame from read_state's records."""
    return poses_frame(head["step"], head["time"], head["kinetic"], head["potential"], bodies["id"], bodies["x"],
                       bodies["q"])


def contacts_frame(step, points, normals):
    """points (k, 3) m and normals (k, 3) unit, world frame -> bytes."""
    points = np.asarray(points, np.float64).reshape(-1, 3)
    rows = np.hstack([points, np.asarray(normals, np.float64).reshape(-1, 3)])
    head = np.array([CONTACTS, step, len(points)], dtype=np.float64)
    return head.astype("<f8").tobytes() + rows.astype("<f8").tobytes()


def contacts_from_payload(payload):
    """A CONTACTS frame from a CONTACTS payload (Client.contacts_payload), or
    None when it is not exactly one contacts_t of this layout."""
    if len(payload) < 28 or payload[:8] != _CONTACTS_FP:
        return None
    step = int(np.frombuffer(payload, ">i8", count=1, offset=16)[0])
    skip = int(np.frombuffer(payload, ">i4", count=1, offset=24)[0])   # method's length, with its NUL
    at = 28 + skip + 1                                                  # past the method and value_kind
    if skip < 1 or len(payload) < at + 4:
        return None
    n = int(np.frombuffer(payload, ">i4", count=1, offset=at)[0])
    if n < 0 or len(payload) != at + 4 + n * _CONTACT.itemsize:
        return None
    rows = np.frombuffer(payload, _CONTACT, count=n, offset=at + 4)
    return contacts_frame(step, rows["point"], rows["normal"])


def poses_from_catalog(catalog):
    """A POSES frame from a snapshot's catalog: what a paused server shows
    before it publishes any STATE (energies unknown: NaN)."""
    bodies = catalog["bodies"]
    return poses_frame(catalog["step"], catalog["time"], float("nan"), float("nan"), [b["id"] for b in bodies],
                       [b["x"] for b in bodies], [b["q"] for b in bodies])


RAYS = 3.0
RAY_WIDTH = 11       # source body id (0: origin in the world), origin (3), end (3), hit (0 or 1), normal (3)


def rays_frame(step, kind, bodies, origins, ends, hit, normals=None):
    """A RAYS frame: ``kind`` 0 for a ray cast (origins in the world), 1 for
    the range sensors (origins in the frames of ``bodies``); ends in the
    world, m; the surface's unit normal at each hit, world frame, zero for
    a miss and where the reading has none (range sensors). -> bytes"""
    n = len(hit)
    normals = np.zeros((n, 3)) if normals is None else np.asarray(normals, np.float64).reshape(n, 3)
    rows = np.hstack([np.asarray(bodies, np.float64).reshape(n, 1), np.asarray(origins, np.float64).reshape(n, 3),
                      np.asarray(ends, np.float64).reshape(n, 3), np.asarray(hit, np.float64).reshape(n, 1),
                      np.where(np.asarray(hit, bool).reshape(n, 1), normals, 0.0)])
    head = np.array([RAYS, step, kind, n], dtype=np.float64)
    return head.astype("<f8").tobytes() + rows.astype("<f8").tobytes()
