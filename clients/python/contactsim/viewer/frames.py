"""The binary WebSocket frames the page draws from (docs/viewer.md).

Each is a little-endian Float64Array whose first value names it, so the page
reads a 1,000-body pose frame without parsing text:

* POSES:    [1, step, time, kinetic J, potential J, n, then per body id, px, py, pz, qw, qx, qy, qz]
* CONTACTS: [2, step, n, then per contact px, py, pz, nx, ny, nz]

Doubles keep the positions exact: the page shows what STATE says.
"""
import numpy as np

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


def poses_from_state(state_msg):
    """A POSES frame from a decoded state_t (contactsim.State.raw)."""
    bodies = state_msg.bodies
    flat = np.fromiter((v for b in bodies for v in (b.id, *b.position, *b.orientation)),
                       dtype=np.float64, count=len(bodies) * POSE_WIDTH).reshape(-1, POSE_WIDTH)
    return poses_frame(state_msg.step, state_msg.time, state_msg.kinetic_energy, state_msg.potential_energy,
                       flat[:, 0], flat[:, 1:4], flat[:, 4:8])


def contacts_frame(step, points, normals):
    """points (k, 3) m and normals (k, 3) unit, world frame -> bytes."""
    points = np.asarray(points, np.float64).reshape(-1, 3)
    rows = np.hstack([points, np.asarray(normals, np.float64).reshape(-1, 3)])
    head = np.array([CONTACTS, step, len(points)], dtype=np.float64)
    return head.astype("<f8").tobytes() + rows.astype("<f8").tobytes()


def contacts_from_msg(msg):
    """A CONTACTS frame from a decoded contacts_t."""
    cs = msg.contacts
    return contacts_frame(msg.step, [c.point for c in cs], [c.normal for c in cs])


def poses_from_catalog(catalog):
    """A POSES frame from a snapshot's catalog: what a paused server shows
    before it publishes any STATE (energies unknown: NaN)."""
    bodies = catalog["bodies"]
    return poses_frame(catalog["step"], catalog["time"], float("nan"), float("nan"), [b["id"] for b in bodies],
                       [b["x"] for b in bodies], [b["q"] for b in bodies])
