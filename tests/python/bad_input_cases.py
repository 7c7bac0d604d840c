"""A catalogue of deliberate bad inputs, every channel and op, for
test_bad_inputs.py and scripts/bad_input_table.py (which renders the cases
with their actual replies into docs/reliability.md).

Each Case sends one command to a server holding SCENE (ids in IDS) and
returns the server's reply_t; ``code`` is the reply code it must get and
``words`` what its message must contain (the field and the value).
"""
import math
import threading
from collections import namedtuple
from pathlib import Path

import numpy as np

import contactsim
from contactsim import body_cmd_t as B, input_t, joint_cmd_t as J, reply_t as R, scene_cmd_t as S

import height_maps
import lcm_wire

NAN, INF = math.nan, math.inf
MISSING = 999999  # no body or joint has this id

SCENE = """
gravity { z: -9.81 }
bodies { name: "ground" plane { normal { z: 1 } offset: 0 } }
bodies { name: "ball" sphere { radius: 0.1 } position { z: 0.5 } mass: 2 }
bodies { name: "crate" box { half_extents { x: 0.1 y: 0.2 z: 0.05 } } position { x: 1 z: 0.3 } density: 500 }
bodies { name: "slider" box { half_extents { x: 0.1 y: 0.1 z: 0.1 } } position { x: -1 z: 1 } kinematic: true
         linear_velocity { x: 0.1 } }
bodies { name: "pillar" box { half_extents { x: 0.1 y: 0.1 z: 1 } } position { x: 3 z: 1 } fixed: true }
bodies { name: "door" box { half_extents { x: 0.4 y: 0.02 z: 0.8 } } position { x: -2 y: 2 z: 0.85 } }
bodies { name: "bob" sphere { radius: 0.05 } position { x: 2 y: 2 z: 1 } }
joints { kind: "hinge" body_a: "door" anchor { x: -2.4 y: 2 z: 0.85 } axis { z: 1 } limits { lower: -1 upper: 1 } }
joints { kind: "distance" body_a: "bob" anchor { x: 2 y: 2 z: 2 } }
"""
IDS = dict(ground=1, ball=2, crate=3, slider=4, pillar=5, door=6, bob=7)
JOINTS = (1, 2)

Case = namedtuple("Case", "id channel op send code words gap", defaults=(None,))
Case.__doc__ = """One bad input. ``gap``: why the server's answer falls short today
(the test expects it to, strictly, so that a fix is noticed); None for most."""


# ------------------------------------------------------------ senders
def _reply(client, channel, msg):
    """Sends msg with the client's id and a fresh request id; -> reply_t."""
    try:
        ok = client._send(channel, msg)
        r = R()
        r.client_id, r.code, r.message, r.step, r.time = client.client_id, ok.code, ok.message, ok.step, ok.time
        return r
    except contactsim.TimeoutError:
        raise
    except contactsim.CommandError as e:
        return e.reply


def raw(client, channel, payload, timeout=5.0):
    """Publishes bytes on a command channel and returns the reply they get:
    the first reply to this client's id, or to no id (DECODE_ERROR replies
    name no client when the header cannot be read), after the publish."""
    got, arrived = [], threading.Event()

    def on_reply(r):
        if r.client_id in ("", client.client_id) and r.request_id in (-1, RAW_REQUEST_ID):
            got.append(r)
            arrived.set()

    remove = client.on_reply(on_reply)
    try:
        client._lc.publish(client.channels[channel], payload)
        if not arrived.wait(timeout):
            raise contactsim.TimeoutError("no reply to %d raw bytes on %s within %gs" % (len(payload), channel, timeout))
    finally:
        remove()
    return got[0]


RAW_REQUEST_ID = 777000001


def body(op, body_id=0, **fields):
    m = B()
    m.op = op
    m.body_id = body_id
    m.orientation = [1.0, 0.0, 0.0, 0.0]
    for k, v in fields.items():
        setattr(m, k, v)
    return m


def add(shape, **fields):
    defaults = dict(radius=0.1, half_extents=[0.1, 0.1, 0.1], half_length=0.1, position=[10.0, 10.0, 1.0])
    if shape == B.PLANE:
        defaults = dict(plane_normal=[0.0, 0.0, 1.0], fixed=True)
    defaults.update(fields)
    return body(B.ADD, shape=shape, **defaults)


def compound_part(shape, position=(0.0, 0.0, 0.0)):
    """The part fields of a one-part COMPOUND (a 0.1 m part of `shape`)."""
    return dict(num_parts=1, part_shape=[shape], part_radius=[0.1], part_half_extents=[[0.1, 0.1, 0.1]],
                part_half_length=[0.1], part_num_points=[0], num_part_points=0, part_points=[],
                part_position=[list(position)], part_orientation=[[1.0, 0.0, 0.0, 0.0]])


def scene(op, **fields):
    m = S()
    m.op = op
    for k, v in fields.items():
        setattr(m, k, v)
    return m


def joint(op, **fields):
    m = J()
    m.op = op
    m.anchor = [0.0, 0.0, 2.0]
    for k, v in fields.items():
        setattr(m, k, v)
    return m


def method(name, params):
    return scene(S.SET_METHOD, method=name, num_params=len(params), param_names=list(params),
                 param_values=list(params.values()))


def cube_points(n):
    """n points on a 10 cm sphere (a valid hull), for point-count limits."""
    pts = []
    for i in range(n):
        z = 1.0 - 2.0 * (i + 0.5) / n
        r = math.sqrt(max(0.0, 1.0 - z * z))
        a = i * 2.399963
        pts.append([0.1 * r * math.cos(a), 0.1 * r * math.sin(a), 0.1 * z])
    return pts


def send(channel, msg_factory):
    return lambda c: _reply(c, channel, msg_factory())


def bodycmd(factory):
    return send("BODY_CMD", factory)


def scenecmd(factory):
    return send("SCENE_CMD", factory)


def jointcmd(factory):
    return send("JOINT_CMD", factory)


def inputcmd(factory):
    return send("INPUT", factory)


def as_controller(factory):
    """Registers the client as a controller, sends the input, releases."""
    def run(c):
        c.register_controller()
        try:
            return _reply(c, "INPUT", factory(c))
        finally:
            c.release_controller()
    return run


def inp(step=1, bodies=(), forces=None, torques=None, num=None):
    m = input_t()
    m.step = step
    m.body_ids = list(bodies)
    m.forces = forces if forces is not None else [[0.0, 0.0, 1.0]] * len(m.body_ids)
    m.torques = torques if torques is not None else [[0.0, 0.0, 0.0]] * len(m.body_ids)
    m.num_bodies = len(m.body_ids) if num is None else num
    return m


def actuator(joints=(), op=None, **fields):
    """An ACTUATOR_CMD SET (or op) of the fields on the joints."""
    m = contactsim.actuator_cmd_t()
    m.op = contactsim.actuator_cmd_t.SET if op is None else op
    m.joints = joint_command(joints, **fields)
    return m


def joint_command(joints=(), model=0, num_ids=None, fields=None, **values):
    """A joint_command_t: one value per joint of each field given."""
    from contactsim.actuators import FIELDS
    m = contactsim.joint_command_t()
    m.model_id, m.joint_ids = model, list(joints)
    m.num_ids = len(m.joint_ids) if num_ids is None else num_ids
    n = max([len(m.joint_ids)] + [len(v) for v in values.values()])
    m.num_joints = n
    m.fields = 0
    for name, (bit, column) in FIELDS.items():
        if name in values:
            m.fields |= bit
        setattr(m, column, list(values.get(name, [0.0] * n)))
    if fields is not None:
        m.fields = fields
    return m


def actuatorcmd(factory):
    return send("ACTUATOR_CMD", factory)


def inp_joints(c, joints, **values):
    """An input for the next step with a joint command."""
    m = inp(c.state().step + 1)
    m.joints = joint_command(joints, **values)
    return m


def corrupt(msg, cut=None, patch=None):
    """msg encoded with the raw request id; cut to `cut` bytes or with bytes
    at (offset, bytes) in `patch`, the offset counted from the end when < 0."""
    def make(c):
        msg.client_id = c.client_id
        msg.request_id = RAW_REQUEST_ID
        b = bytearray(msg.encode())
        if cut is not None:
            b = b[:cut]
        if patch is not None:
            off, data = patch
            off = off if off >= 0 else len(b) + off
            b[off:off + len(data)] = data
        return bytes(b)
    return make


def rawcmd(channel, make):
    return lambda c: raw(c, channel, make(c))


def after_client_id(c):
    """Offset of the field after client_id in an encoded command of this client."""
    return 8 + 4 + len(c.client_id.encode()) + 1


def recount(factory, field, value):
    """The message encoded with the raw request id, then its count field
    set to value on the wire (the generated encoders write as many
    elements as the count says, so a disagreeing count exists only there)."""
    def make(c):
        msg = factory()
        msg.client_id, msg.request_id = c.client_id, RAW_REQUEST_ID
        data = bytearray(msg.encode())
        span = next(s for s in lcm_wire.layout(type(msg).__name__, bytes(data)) if s.path == field)
        data[span.offset:span.offset + 4] = value.to_bytes(4, "big", signed=True)
        return bytes(data)
    return make


def string_length_at(offset_fn, value):
    def make(c):
        m = scene(S.PAUSE)
        m.client_id, m.request_id = c.client_id, RAW_REQUEST_ID
        b = bytearray(m.encode())
        off = offset_fn(c)
        b[off:off + 4] = value.to_bytes(4, "big", signed=True)
        return bytes(b)
    return make


FILES = {
    "bad-radius.pbtxt": 'bodies { name: "x" sphere { radius: -1 } }\n',
    "syntax.pbtxt": "bodies { sphere { radius: \n",
    "not-a-snapshot.pb": "this is not a snapshot",
}


# height maps the heightfield cases name: what a 16-bit greyscale PNG or a
# raw uint16 file must not be
_SAMPLES = [[0, 1000, 2000], [3000, 4000, 5000]]
HEIGHT_MAPS = {
    "grey8.png": lambda: height_maps.png_bytes(_SAMPLES, bit_depth=8),
    "rgb16.png": lambda: height_maps.png_bytes([[[v] * 3 for v in row] for row in _SAMPLES], colour=height_maps.RGB),
    "huge16.png": lambda: height_maps.png_bytes(_SAMPLES, size=(4097, 4097)),   # a header claiming 4097 x 4097
    "short.raw": lambda: bytes(10),                                               # 5 samples, not 2 x 3
    # 9 million samples: within kMaxHeightSamples, but 72 MB of heights, over a journal record
    "big16.png": lambda: height_maps.png_bytes(np.zeros((3000, 3000), dtype=np.uint16)),
}


def write_files(tmp):
    """Writes the files some cases name into the folder tmp."""
    for name, text in FILES.items():
        (Path(tmp) / name).write_text(text)
    for name, make in HEIGHT_MAPS.items():
        (Path(tmp) / name).write_bytes(make())


# ---------------------------------------------------------------- cases
IA, NF, FP, DE, RE = R.INVALID_ARGUMENT, R.NOT_FOUND, R.FAILED_PRECONDITION, R.DECODE_ERROR, R.RESOURCE_EXHAUSTED
ball, crate, slider, pillar, ground, door, bob = (IDS[k] for k in ("ball", "crate", "slider", "pillar", "ground", "door",
                                                                  "bob"))


def cases(tmp):
    """Every case; ``tmp`` is the folder of write_files (scene and snapshot files some cases name)."""
    tmp = Path(tmp)
    bad_scene, syntax, not_snapshot = (str(tmp / n) for n in FILES)
    c = [
        # ---- BODY_CMD ADD: every field group non-finite or out of range
        Case("add_sphere_nan_radius", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, radius=NAN)), IA, ["radius", "nan"]),
        Case("add_sphere_negative_radius", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, radius=-1.0)), IA, ["radius", "-1"]),
        Case("add_sphere_inf_radius", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, radius=INF)), IA, ["radius", "inf"]),
        Case("add_box_negative_half_extent", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.BOX, half_extents=[0.1, -0.2, 0.1])), IA, ["half_extents", "-0.2"]),
        Case("add_box_nan_half_extent", "BODY_CMD", "ADD", bodycmd(lambda: add(B.BOX, half_extents=[NAN, 0.1, 0.1])), IA,
             ["half_extents", "nan"]),
        Case("add_capsule_negative_half_length", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.CAPSULE, half_length=-0.3)), IA, ["half_length", "-0.3"]),
        Case("add_capsule_zero_radius", "BODY_CMD", "ADD", bodycmd(lambda: add(B.CAPSULE, radius=0.0)), IA, ["radius", "0"]),
        Case("add_plane_zero_normal", "BODY_CMD", "ADD", bodycmd(lambda: add(B.PLANE, plane_normal=[0.0, 0.0, 0.0])), IA,
             ["plane_normal"]),
        Case("add_plane_nan_normal", "BODY_CMD", "ADD", bodycmd(lambda: add(B.PLANE, plane_normal=[0.0, NAN, 1.0])), IA,
             ["plane_normal", "nan"]),
        Case("add_plane_inf_offset", "BODY_CMD", "ADD", bodycmd(lambda: add(B.PLANE, plane_offset=INF)), IA,
             ["plane_offset", "inf"]),
        Case("add_convex_two_points", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.CONVEX, num_points=2, points=[[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]])), IA, ["points"]),
        Case("add_convex_nan_point", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.CONVEX, num_points=4, points=[[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0],
                                                                 [0.0, 0.0, NAN]])), IA, ["points", "nan"]),
        Case("add_convex_count_too_small", "BODY_CMD", "ADD",
             rawcmd("BODY_CMD", recount(lambda: add(B.CONVEX, num_points=5, points=cube_points(5)), "num_points", 4)), DE,
             ["undecodable", "body_cmd_t"]),
        Case("add_convex_negative_count", "BODY_CMD", "ADD",
             rawcmd("BODY_CMD", recount(lambda: add(B.CONVEX, num_points=5, points=cube_points(5)), "num_points", -1)), DE,
             ["undecodable", "body_cmd_t"]),
        Case("add_convex_too_many_points", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.CONVEX, num_points=5000, points=cube_points(5000))), RE, ["max_convex_points", "5000"]),
        Case("add_compound_no_parts", "BODY_CMD", "ADD", bodycmd(lambda: add(B.COMPOUND)), IA,
             ["a compound takes 1 to 64 parts, got 0"]),
        Case("add_compound_plane_part", "BODY_CMD", "ADD", bodycmd(lambda: add(B.COMPOUND, **compound_part(B.PLANE))),
             IA, ["parts[0].type", "plane"]),
        Case("add_compound_nan_part_position", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.COMPOUND, **compound_part(B.SPHERE, position=[0.0, NAN, 0.0]))), IA,
             ["parts[0].position", "nan"]),
        Case("add_mesh_empty", "BODY_CMD", "ADD", bodycmd(lambda: add(B.MESH, fixed=True)), IA,
             ["a mesh needs vertices and indices", "0 vertices"]),
        Case("add_mesh_index_out_of_range", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, num_points=3, points=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], num_mesh_indices=3,
                                 mesh_indices=[0, 1, 3])), IA, ["mesh index 2 is 3", "out of range"]),
        Case("add_mesh_nan_vertex", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, num_points=3, points=[[0.0, 0.0, 0.0], [NAN, 0.0, 0.0],
                                                                          [0.0, 1.0, 0.0]],
                                 num_mesh_indices=3, mesh_indices=[0, 1, 2])), IA, ["mesh vertex 1", "not finite"]),
        Case("add_mesh_inf_vertex", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, num_points=3, points=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0],
                                                                          [0.0, INF, 0.0]],
                                 num_mesh_indices=3, mesh_indices=[0, 1, 2])), IA, ["mesh vertex 2", "not finite"]),
        Case("add_mesh_indices_not_triangles", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, num_points=3, points=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], num_mesh_indices=4,
                                 mesh_indices=[0, 1, 2, 0])), IA, ["three per triangle", "4"]),
        Case("add_mesh_all_zero_area", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, num_points=3, points=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0],
                                                                          [2.0, 0.0, 0.0]],
                                 num_mesh_indices=3, mesh_indices=[0, 1, 2])), IA, ["zero area"]),
        Case("add_mesh_missing_file", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, fixed=True, mesh_path="/nonexistent/floor.obj")), NF, ["floor.obj"]),
        Case("add_mesh_dynamic", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.MESH, kinematic=True, num_points=3, points=[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], num_mesh_indices=3,
                                 mesh_indices=[0, 1, 2])), IA, ["mesh is always static"]),
        Case("add_heightfield_wrong_shape", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_rows=3, height_cols=3, num_heights=4,
                                 heights=[0.0] * 4, height_spacing=[0.1, 0.1])), IA, ["rows x cols = 3 x 3", "got 4"]),
        Case("add_heightfield_nan_height", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_rows=2, height_cols=2, num_heights=4,
                                 heights=[0.0, 0.0, NAN, 0.0], height_spacing=[0.1, 0.1])), IA,
             ["height 2 (row 1, col 0)", "finite"]),
        Case("add_heightfield_zero_spacing", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_rows=2, height_cols=2, num_heights=4,
                                 heights=[0.0] * 4, height_spacing=[0.0, 0.1])), IA, ["spacing", "0"]),
        Case("add_heightfield_missing_file", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path="/nonexistent/terrain.png",
                                 height_spacing=[0.1, 0.1])), NF, ["terrain.png"]),
        Case("add_heightfield_8bit_png", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "grey8.png"),
                                 height_spacing=[0.1, 0.1])), IA, ["grey8.png", "8-bit greyscale", "16-bit greyscale"]),
        Case("add_heightfield_colour_png", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "rgb16.png"),
                                 height_spacing=[0.1, 0.1])), IA, ["rgb16.png", "16-bit RGB", "16-bit greyscale"]),
        Case("add_heightfield_png_too_large", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "huge16.png"),
                                 height_spacing=[0.1, 0.1])), RE, ["4097 x 4097", "kMaxHeightSamples"]),
        Case("add_heightfield_raw_wrong_size", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "short.raw"), height_rows=2,
                                 height_cols=3, height_spacing=[0.1, 0.1])), IA, ["short.raw", "10 bytes", "2 x 3"]),
        Case("add_heightfield_raw_too_large", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "short.raw"), height_rows=5000,
                                 height_cols=5000, height_spacing=[0.1, 0.1])), RE, ["5000 x 5000", "kMaxHeightSamples"]),
        Case("add_heightfield_over_a_journal_record", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "big16.png"),
                                 height_spacing=[0.1, 0.1])), RE, ["3000 x 3000", "journal's record limit"]),
        Case("add_heightfield_path_and_heights", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.HEIGHTFIELD, fixed=True, height_path=str(tmp / "short.raw"), height_rows=2,
                                 height_cols=2, num_heights=4, heights=[0.0] * 4, height_spacing=[0.1, 0.1])), IA,
             ["height_path or heights"]),
        Case("add_inertia_triangle_inequality", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.SPHERE, mass=1.0, has_inertia=True, inertia=[1.0, 1.0, 3.0, 0.0, 0.0, 0.0])), IA,
             ["inertia", "triangle inequality"]),
        Case("add_inertia_not_positive", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.SPHERE, mass=1.0, has_inertia=True, inertia=[1.0, -1.0, 1.0, 0.0, 0.0, 0.0])), IA,
             ["inertia", "positive definite"]),
        Case("add_nan_position", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, position=[NAN, 0.0, 1.0])), IA,
             ["position", "nan"]),
        Case("add_inf_position", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, position=[0.0, -INF, 1.0])), IA,
             ["position", "inf"]),
        Case("add_nan_orientation", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, orientation=[NAN, 0.0, 0.0, 0.0])),
             IA, ["orientation", "nan"]),
        Case("add_tiny_quaternion", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, orientation=[1e-12, 0.0, 0.0, 0.0])),
             IA, ["orientation", "norm"]),
        Case("add_inf_velocity", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, linear_velocity=[INF, 0.0, 0.0])), IA,
             ["velocity", "inf"]),
        Case("add_nan_angular_velocity", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.SPHERE, angular_velocity=[0.0, NAN, 0.0])), IA, ["angular_velocity", "nan"]),
        Case("add_negative_mass", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, mass=-1.0)), IA, ["mass", "-1"]),
        Case("add_nan_mass", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, mass=NAN)), IA, ["mass", "nan"]),
        Case("add_negative_density", "BODY_CMD", "ADD", bodycmd(lambda: add(B.BOX, density=-5.0)), IA, ["density", "-5"]),
        Case("add_mass_and_density", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, mass=1.0, density=1000.0)), IA,
             ["mass", "density"]),
        Case("add_restitution_above_one", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.SPHERE, has_restitution=True, restitution=1.5)), IA, ["restitution", "1.5"]),
        Case("add_nan_restitution", "BODY_CMD", "ADD",
             bodycmd(lambda: add(B.SPHERE, has_restitution=True, restitution=NAN)), IA, ["restitution", "nan"]),
        Case("add_negative_friction", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, has_friction=True, friction=-0.1)),
             IA, ["friction", "-0.1"]),
        Case("add_inf_friction", "BODY_CMD", "ADD", bodycmd(lambda: add(B.SPHERE, has_friction=True, friction=INF)), IA,
             ["friction", "inf"]),
        Case("add_fixed_and_kinematic", "BODY_CMD", "ADD", bodycmd(lambda: add(B.BOX, fixed=True, kinematic=True)), IA,
             ["fixed", "kinematic"]),
        Case("add_kinematic_plane", "BODY_CMD", "ADD", bodycmd(lambda: add(B.PLANE, kinematic=True, fixed=False)), IA,
             ["plane", "kinematic"]),
        Case("add_unknown_shape", "BODY_CMD", "ADD", bodycmd(lambda: add(9)), IA, ["shape", "9"]),
        Case("add_oversized_name", "BODY_CMD", "ADD",
             rawcmd("BODY_CMD", lambda c: _with_client_id(add(B.SPHERE, name="n" * 200000), c.client_id)), RE,
             ["body_cmd_t", "131072"]),
        # ---- BODY_CMD, the other ops
        Case("body_unknown_op", "BODY_CMD", "op 42", bodycmd(lambda: body(42, ball)), IA, ["op", "42"]),
        Case("remove_unknown_body", "BODY_CMD", "REMOVE", bodycmd(lambda: body(B.REMOVE, MISSING)), NF, [str(MISSING)]),
        Case("remove_negative_id", "BODY_CMD", "REMOVE", bodycmd(lambda: body(B.REMOVE, -3)), NF, ["-3"]),
        Case("set_pose_unknown_body", "BODY_CMD", "SET_POSE",
             bodycmd(lambda: body(B.SET_POSE, MISSING, position=[0.0, 0.0, 1.0])), NF, [str(MISSING)]),
        Case("set_pose_nan_position", "BODY_CMD", "SET_POSE",
             bodycmd(lambda: body(B.SET_POSE, ball, position=[0.0, NAN, 1.0])), IA, ["position", "nan"]),
        Case("set_pose_zero_quaternion", "BODY_CMD", "SET_POSE",
             bodycmd(lambda: body(B.SET_POSE, ball, position=[0.0, 0.0, 1.0], orientation=[0.0, 0.0, 0.0, 0.0])), IA,
             ["orientation"]),
        Case("set_pose_inf_quaternion", "BODY_CMD", "SET_POSE",
             bodycmd(lambda: body(B.SET_POSE, ball, position=[0.0, 0.0, 1.0], orientation=[1.0, INF, 0.0, 0.0])), IA,
             ["orientation", "inf"]),
        Case("set_pose_tiny_quaternion", "BODY_CMD", "SET_POSE",
             bodycmd(lambda: body(B.SET_POSE, ball, position=[0.0, 0.0, 1.0], orientation=[0.0, 0.0, 1e-11, 0.0])), IA,
             ["orientation", "norm"]),
        Case("set_velocity_unknown_body", "BODY_CMD", "SET_VELOCITY", bodycmd(lambda: body(B.SET_VELOCITY, MISSING)), NF,
             [str(MISSING)]),
        Case("set_velocity_nan_linear", "BODY_CMD", "SET_VELOCITY",
             bodycmd(lambda: body(B.SET_VELOCITY, ball, linear_velocity=[NAN, 0.0, 0.0])), IA, ["linear_velocity", "nan"]),
        Case("set_velocity_inf_angular", "BODY_CMD", "SET_VELOCITY",
             bodycmd(lambda: body(B.SET_VELOCITY, ball, angular_velocity=[0.0, 0.0, -INF])), IA,
             ["angular_velocity", "inf"]),
        Case("set_velocity_static_body", "BODY_CMD", "SET_VELOCITY",
             bodycmd(lambda: body(B.SET_VELOCITY, pillar, linear_velocity=[1.0, 0.0, 0.0])), FP,
             [str(pillar), "static"]),
        Case("apply_force_nan_force", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, ball, force=[0.0, 0.0, NAN])), IA, ["force", "nan"]),
        Case("apply_force_inf_torque", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, ball, torque=[INF, 0.0, 0.0])), IA, ["torque", "inf"]),
        Case("apply_force_negative_duration", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, ball, force=[0.0, 0.0, 1.0], duration=-1.0)), IA, ["duration", "-1"]),
        Case("apply_force_nan_duration", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, ball, force=[0.0, 0.0, 1.0], duration=NAN)), IA, ["duration", "nan"]),
        Case("apply_force_kinematic_body", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, slider, force=[0.0, 0.0, 1.0])), FP, [str(slider), "kinematic"]),
        Case("apply_force_unknown_body", "BODY_CMD", "APPLY_FORCE",
             bodycmd(lambda: body(B.APPLY_FORCE, MISSING, force=[0.0, 0.0, 1.0])), NF, [str(MISSING)]),
        Case("apply_impulse_nan_impulse", "BODY_CMD", "APPLY_IMPULSE",
             bodycmd(lambda: body(B.APPLY_IMPULSE, ball, impulse=[NAN, 0.0, 0.0])), IA, ["impulse", "nan"]),
        Case("apply_impulse_inf_point", "BODY_CMD", "APPLY_IMPULSE",
             bodycmd(lambda: body(B.APPLY_IMPULSE, ball, impulse=[1.0, 0.0, 0.0], has_point=True, point=[0.0, INF, 0.0])),
             IA, ["point", "inf"]),
        Case("apply_impulse_static_body", "BODY_CMD", "APPLY_IMPULSE",
             bodycmd(lambda: body(B.APPLY_IMPULSE, ground, impulse=[1.0, 0.0, 0.0])), FP, [str(ground), "static"]),
        Case("set_mass_neither", "BODY_CMD", "SET_MASS", bodycmd(lambda: body(B.SET_MASS, ball)), IA, ["mass", "density"]),
        Case("set_mass_negative", "BODY_CMD", "SET_MASS", bodycmd(lambda: body(B.SET_MASS, ball, mass=-2.0)), IA,
             ["mass", "-2"]),
        Case("set_mass_nan_density", "BODY_CMD", "SET_MASS", bodycmd(lambda: body(B.SET_MASS, ball, density=NAN)), IA,
             ["density", "nan"]),
        Case("set_mass_kinematic_body", "BODY_CMD", "SET_MASS", bodycmd(lambda: body(B.SET_MASS, slider, mass=3.0)), FP,
             [str(slider), "kinematic"]),
        Case("set_material_negative_restitution", "BODY_CMD", "SET_MATERIAL",
             bodycmd(lambda: body(B.SET_MATERIAL, ball, has_restitution=True, restitution=-0.5)), IA,
             ["restitution", "-0.5"]),
        Case("set_material_nan_friction", "BODY_CMD", "SET_MATERIAL",
             bodycmd(lambda: body(B.SET_MATERIAL, ball, has_friction=True, friction=NAN)), IA, ["friction", "nan"]),
        Case("set_material_unknown_body", "BODY_CMD", "SET_MATERIAL",
             bodycmd(lambda: body(B.SET_MATERIAL, MISSING, has_friction=True, friction=0.3)), NF, [str(MISSING)]),
        Case("set_filter_unknown_body", "BODY_CMD", "SET_FILTER",
             bodycmd(lambda: body(B.SET_FILTER, MISSING, collision_category=2, collision_mask=1)), NF, [str(MISSING)]),
        Case("set_filter_world", "BODY_CMD", "SET_FILTER",
             bodycmd(lambda: body(B.SET_FILTER, 0, collision_category=2, collision_mask=1)), NF, ["0", "world"]),
        # ---- SCENE_CMD
        Case("scene_op_zero", "SCENE_CMD", "op 0", scenecmd(lambda: scene(0)), IA, ["op", "0"]),
        Case("scene_unknown_op", "SCENE_CMD", "op 99", scenecmd(lambda: scene(99)), IA, ["op", "99"]),
        Case("load_scene_missing_file", "SCENE_CMD", "LOAD_SCENE",
             scenecmd(lambda: scene(S.LOAD_SCENE, path="/nonexistent/scene.pbtxt")), None, ["/nonexistent/scene.pbtxt"]),
        Case("load_scene_empty_path", "SCENE_CMD", "LOAD_SCENE", scenecmd(lambda: scene(S.LOAD_SCENE, path="")), None,
             ["path"]),
        Case("load_scene_syntax_error", "SCENE_CMD", "LOAD_SCENE", scenecmd(lambda: scene(S.LOAD_SCENE, path=syntax)),
             IA, [syntax]),
        Case("load_scene_negative_radius", "SCENE_CMD", "LOAD_SCENE",
             scenecmd(lambda: scene(S.LOAD_SCENE, path=bad_scene)), IA, ["radius", "-1"]),
        Case("set_gravity_nan", "SCENE_CMD", "SET_GRAVITY", scenecmd(lambda: scene(S.SET_GRAVITY, gravity=[0.0, 0.0, NAN])),
             IA, ["gravity", "nan"]),
        Case("set_gravity_inf", "SCENE_CMD", "SET_GRAVITY", scenecmd(lambda: scene(S.SET_GRAVITY, gravity=[INF, 0.0, 0.0])),
             IA, ["gravity", "inf"]),
        Case("set_timestep_zero", "SCENE_CMD", "SET_TIMESTEP", scenecmd(lambda: scene(S.SET_TIMESTEP, dt=0.0)), IA,
             ["dt", "0"]),
        Case("set_timestep_negative", "SCENE_CMD", "SET_TIMESTEP", scenecmd(lambda: scene(S.SET_TIMESTEP, dt=-0.01)), IA,
             ["dt", "-0.01"]),
        Case("set_timestep_nan", "SCENE_CMD", "SET_TIMESTEP", scenecmd(lambda: scene(S.SET_TIMESTEP, dt=NAN)), IA,
             ["dt", "nan"]),
        Case("set_timestep_too_large", "SCENE_CMD", "SET_TIMESTEP", scenecmd(lambda: scene(S.SET_TIMESTEP, dt=1.0)), IA,
             ["dt", "1"]),
        Case("set_method_unknown", "SCENE_CMD", "SET_METHOD", scenecmd(lambda: method("nosuch", {})), NF,
             ["nosuch", "known"]),
        Case("set_method_empty_name", "SCENE_CMD", "SET_METHOD", scenecmd(lambda: method("", {})), NF, ['""']),
        Case("set_method_unknown_param", "SCENE_CMD", "SET_METHOD",
             scenecmd(lambda: method("impulse", {"nosuch_param": "1"})), IA, ["nosuch_param"]),
        Case("set_method_param_not_a_number", "SCENE_CMD", "SET_METHOD",
             scenecmd(lambda: method("impulse", {"iterations": "abc"})), IA, ["iterations", "abc"]),
        Case("set_method_param_out_of_range", "SCENE_CMD", "SET_METHOD",
             scenecmd(lambda: method("impulse", {"iterations": "-3"})), IA, ["iterations", "-3"]),
        Case("set_method_count_too_large", "SCENE_CMD", "SET_METHOD",
             rawcmd("SCENE_CMD", recount(lambda: method("impulse", {"iterations": "10"}), "num_params", 2)), DE,
             ["undecodable", "scene_cmd_t"]),
        Case("step_zero", "SCENE_CMD", "STEP", scenecmd(lambda: scene(S.STEP, steps=0)), IA, ["steps", "0"]),
        Case("step_negative", "SCENE_CMD", "STEP", scenecmd(lambda: scene(S.STEP, steps=-5)), IA, ["steps", "-5"]),
        Case("step_too_many", "SCENE_CMD", "STEP", scenecmd(lambda: scene(S.STEP, steps=2000000000)), IA,
             ["steps", "2000000000"]),
        Case("set_mode_unknown", "SCENE_CMD", "SET_MODE", scenecmd(lambda: scene(S.SET_MODE, mode=7)), IA, ["mode", "7"]),
        Case("set_mode_negative_rtf", "SCENE_CMD", "SET_MODE",
             scenecmd(lambda: scene(S.SET_MODE, mode=S.REALTIME, real_time_factor=-1.0)), IA, ["real_time_factor", "-1"]),
        Case("set_mode_nan_rtf", "SCENE_CMD", "SET_MODE",
             scenecmd(lambda: scene(S.SET_MODE, mode=S.REALTIME, real_time_factor=NAN)), IA, ["real_time_factor", "nan"]),
        Case("snapshot_name_and_path", "SCENE_CMD", "SNAPSHOT",
             scenecmd(lambda: scene(S.SNAPSHOT, name="a", path=str(tmp / "a.pb"))), IA, ["name", "path"]),
        Case("snapshot_neither", "SCENE_CMD", "SNAPSHOT", scenecmd(lambda: scene(S.SNAPSHOT)), IA, ["name", "path"]),
        Case("snapshot_bad_name", "SCENE_CMD", "SNAPSHOT", scenecmd(lambda: scene(S.SNAPSHOT, name="../etc/x")), IA,
             ["name", "../etc/x"]),
        Case("snapshot_long_name", "SCENE_CMD", "SNAPSHOT", scenecmd(lambda: scene(S.SNAPSHOT, name="s" * 65)), IA,
             ["name", "s" * 65]),
        Case("snapshot_unwritable_path", "SCENE_CMD", "SNAPSHOT",
             scenecmd(lambda: scene(S.SNAPSHOT, path="/nonexistent/dir/snap.pb")), None, ["/nonexistent/dir/snap.pb"]),
        Case("restore_unknown_slot", "SCENE_CMD", "RESTORE", scenecmd(lambda: scene(S.RESTORE, name="nosuch_slot")), NF,
             ["nosuch_slot"]),
        Case("restore_missing_file", "SCENE_CMD", "RESTORE",
             scenecmd(lambda: scene(S.RESTORE, path="/nonexistent/snap.pb")), None, ["/nonexistent/snap.pb"]),
        Case("restore_not_a_snapshot", "SCENE_CMD", "RESTORE", scenecmd(lambda: scene(S.RESTORE, path=not_snapshot)),
             None, [not_snapshot]),
        Case("rewind_negative", "SCENE_CMD", "REWIND", scenecmd(lambda: scene(S.REWIND, target_step=-1)), IA,
             ["target_step", "-1"]),
        Case("rewind_future", "SCENE_CMD", "REWIND", scenecmd(lambda: scene(S.REWIND, target_step=10 ** 9)), None,
             [str(10 ** 9)]),
        Case("register_unknown_late_policy", "SCENE_CMD", "REGISTER_CONTROLLER",
             scenecmd(lambda: scene(S.REGISTER_CONTROLLER, late_policy=9)), IA, ["late_policy", "9"]),
        Case("register_negative_timeout", "SCENE_CMD", "REGISTER_CONTROLLER",
             scenecmd(lambda: scene(S.REGISTER_CONTROLLER, late_policy=S.LATE_REUSE, late_timeout=-1.0)), IA,
             ["late_timeout", "-1"]),
        Case("register_nan_timeout", "SCENE_CMD", "REGISTER_CONTROLLER",
             scenecmd(lambda: scene(S.REGISTER_CONTROLLER, late_timeout=NAN)), IA, ["late_timeout", "nan"]),
        Case("release_unregistered", "SCENE_CMD", "RELEASE_CONTROLLER", scenecmd(lambda: scene(S.RELEASE_CONTROLLER)), None,
             ["not a registered controller"]),
        Case("scene_oversized_path", "SCENE_CMD", "LOAD_SCENE",
             rawcmd("SCENE_CMD", lambda c: _with_client_id(scene(S.LOAD_SCENE, path="/tmp/" + "p" * 100000), c.client_id)),
             RE, ["scene_cmd_t", "65536"]),
        # ---- JOINT_CMD
        Case("joint_unknown_op", "JOINT_CMD", "op 7", jointcmd(lambda: joint(7)), IA, ["op", "7"]),
        Case("joint_unknown_kind", "JOINT_CMD", "ADD", jointcmd(lambda: joint(J.ADD, kind=9, body_a=ball)), IA,
             ["kind", "9"]),
        Case("joint_unknown_body_a", "JOINT_CMD", "ADD", jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=MISSING)), NF,
             ["body_a", str(MISSING)]),
        Case("joint_unknown_body_b", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=ball, body_b=MISSING)), NF, ["body_b", str(MISSING)]),
        Case("joint_body_a_world", "JOINT_CMD", "ADD", jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=0)), IA,
             ["body_a", "0"]),
        Case("joint_to_itself", "JOINT_CMD", "ADD", jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=ball, body_b=ball)),
             IA, ["body_b", str(ball)]),
        Case("joint_nan_anchor", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=ball, anchor=[NAN, 0.0, 1.0])), IA, ["anchor", "nan"]),
        Case("hinge_without_axis", "JOINT_CMD", "ADD", jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball)), IA,
             ["axis"]),
        Case("hinge_zero_axis", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 0.0])), IA, ["axis"]),
        Case("hinge_nan_axis", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, NAN, 1.0])), IA,
             ["axis", "nan"]),
        Case("hinge_nan_limit", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0], has_limits=True,
                                    lower=NAN, upper=1.0)), IA, ["lower", "nan"]),
        Case("hinge_limits_reversed", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0], has_limits=True,
                                    lower=1.0, upper=-1.0)), IA, ["lower", "upper"]),
        Case("hinge_limits_beyond_pi", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0], has_limits=True,
                                    lower=-4.0, upper=0.0)), IA, ["lower", "-4"]),
        Case("prismatic_without_axis", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.PRISMATIC, body_a=ball)), IA, ["axis", "prismatic"]),
        Case("prismatic_limits_reversed", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.PRISMATIC, body_a=ball, has_axis=True, axis=[1.0, 0.0, 0.0],
                                    has_limits=True, lower=0.5, upper=-0.5)), IA, ["lower", "upper"]),
        Case("prismatic_inf_limit", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.PRISMATIC, body_a=ball, has_axis=True, axis=[1.0, 0.0, 0.0],
                                    has_limits=True, lower=-1.0, upper=INF)), IA, ["upper", "inf"]),
        Case("hinge_negative_damping", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0],
                                    has_damping=True, damping=-1.0)), IA, ["damping", "-1"]),
        Case("prismatic_nan_friction", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.PRISMATIC, body_a=ball, has_axis=True, axis=[1.0, 0.0, 0.0],
                                    has_friction=True, friction=NAN)), IA, ["friction", "nan"]),
        Case("ball_with_friction", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=ball, has_friction=True, friction=1.0)), IA,
             ["friction", "ball"]),
        Case("distance_zero_length", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.DISTANCE, body_a=ball, has_length=True, length=0.0)), IA, ["length", "0"]),
        Case("distance_nan_length", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.DISTANCE, body_a=ball, has_length=True, length=NAN)), IA,
             ["length", "nan"]),
        Case("ball_with_axis", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.BALL, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0])), IA,
             ["axis", "ball"]),
        Case("hinge_with_length", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.HINGE, body_a=ball, has_axis=True, axis=[0.0, 0.0, 1.0], has_length=True,
                                    length=1.0)), IA, ["length", "hinge"]),
        Case("joint_two_static_bodies", "JOINT_CMD", "ADD",
             jointcmd(lambda: joint(J.ADD, kind=J.FIXED, body_a=pillar, body_b=ground)), IA, ["dynamic", str(pillar)]),
        Case("joint_remove_unknown", "JOINT_CMD", "REMOVE", jointcmd(lambda: joint(J.REMOVE, joint_id=MISSING)), NF,
             [str(MISSING)]),
        Case("joint_oversized_client_id", "JOINT_CMD", "REMOVE",
             rawcmd("JOINT_CMD", lambda c: _with_client_id(joint(J.REMOVE, joint_id=MISSING), "c" * 8000)), RE,
             ["joint_cmd_t", "4096"]),
        # ---- INPUT
        Case("input_unregistered", "INPUT", "input", inputcmd(lambda: inp(1, [ball])), FP, ["not a registered controller"]),
        Case("input_count_too_large", "INPUT", "input", rawcmd("INPUT", recount(lambda: inp(1, [ball, crate]), "num_bodies", 3)),
             DE, ["undecodable", "input_t"]),
        Case("input_nan_force", "INPUT", "input", as_controller(lambda c: inp(c.state().step + 1, [ball],
                                                                               forces=[[NAN, 0.0, 0.0]])), IA,
             ["forces[0]", "nan"]),
        Case("input_inf_torque", "INPUT", "input", as_controller(lambda c: inp(c.state().step + 1, [ball],
                                                                                torques=[[0.0, INF, 0.0]])), IA,
             ["torques[0]", "inf"]),
        Case("input_past_step", "INPUT", "input", as_controller(lambda c: inp(0, [ball])), FP, ["step 0"]),
        # ---- ACTUATOR_CMD (door is hinge joint 1, bob hangs on distance joint 2)
        Case("actuator_unknown_joint", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([MISSING], kp=[10.0])), NF, ["unknown joint", str(MISSING)]),
        Case("actuator_one_unknown_joint_sets_none", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1, MISSING], kp=[10.0, 10.0])), NF, [str(MISSING)]),
        Case("actuator_distance_joint", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([2], torque=[1.0])), FP, ["joint 2", "distance", "hinge and prismatic"]),
        Case("actuator_unknown_model", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator(model=MISSING, num_ids=0, kp=[1.0])), NF, ["model", str(MISSING)]),
        Case("actuator_nan_target", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], target_position=[NAN])), IA, ["joints[0].target_position", "nan"]),
        Case("actuator_inf_torque", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], torque=[INF])), IA, ["joints[0].torque", "inf"]),
        Case("actuator_negative_kp", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], kp=[-1.0])), IA, ["joints[0].kp", "-1"]),
        Case("actuator_negative_kd", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], kd=[-0.5])), IA, ["joints[0].kd", "-0.5"]),
        Case("actuator_zero_effort_limit", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], effort_limit=[0.0])), IA, ["joints[0].effort_limit", "> 0"]),
        Case("actuator_negative_velocity_limit", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], velocity_limit=[-2.0])), IA, ["joints[0].velocity_limit", "-2"]),
        Case("actuator_ids_and_values_disagree", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], num_ids=1, kp=[1.0, 2.0])), IA, ["num_ids", "num_joints"]),
        Case("actuator_joint_twice", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1, 1], kp=[1.0, 2.0])), IA, ["joint 1", "twice"]),
        Case("actuator_no_field", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], fields=0, kp=[1.0])), IA, ["names no field"]),
        Case("actuator_unknown_field_bit", "ACTUATOR_CMD", "SET",
             actuatorcmd(lambda: actuator([1], fields=-128, kp=[1.0])), IA, ["fields", "-128"]),
        Case("actuator_no_joint", "ACTUATOR_CMD", "CLEAR",
             actuatorcmd(lambda: actuator(op=2)), IA, ["names no joint"]),
        Case("actuator_bad_op", "ACTUATOR_CMD", "-", actuatorcmd(lambda: actuator([1], op=9, kp=[1.0])), IA,
             ["op", "9"]),
        Case("input_joint_unknown", "INPUT", "input", as_controller(lambda c: inp_joints(c, [MISSING], torque=[1.0])),
             NF, ["input for step", str(MISSING)]),
        Case("input_joint_distance", "INPUT", "input", as_controller(lambda c: inp_joints(c, [2], torque=[1.0])), FP,
             ["joint 2", "distance"]),
        Case("input_joint_nan_torque", "INPUT", "input",
             as_controller(lambda c: inp_joints(c, [1], torque=[NAN])), IA, ["joints[0].torque", "nan"]),
        Case("input_joint_negative_kp", "INPUT", "input",
             as_controller(lambda c: inp_joints(c, [1], kp=[-3.0])), IA, ["joints[0].kp", "-3"]),
        Case("input_joint_counts_disagree", "INPUT", "input",
             as_controller(lambda c: inp_joints(c, [1], num_ids=1, kp=[1.0, 1.0])), IA, ["num_ids"]),
        # ---- bytes that are no command
        Case("random_bytes_body", "BODY_CMD", "-", rawcmd("BODY_CMD", lambda c: bytes(range(7, 7 + 64))), DE,
             ["undecodable", "body_cmd_t"]),
        Case("truncated_scene", "SCENE_CMD", "-", rawcmd("SCENE_CMD", corrupt(scene(S.PAUSE), cut=20)), DE,
             ["undecodable", "scene_cmd_t"]),
        Case("zero_string_length_scene", "SCENE_CMD", "PAUSE",
             rawcmd("SCENE_CMD", string_length_at(lambda c: 8, 0)), DE, ["undecodable", "scene_cmd_t"]),
        Case("negative_string_length_scene", "SCENE_CMD", "PAUSE",
             rawcmd("SCENE_CMD", string_length_at(after_client_id_plus_op, -1)), DE,
             ["undecodable", "scene_cmd_t"]),
        Case("huge_count_input", "INPUT", "input", rawcmd("INPUT", recount(lambda: inp(1, [ball]), "num_bodies", 0x7FFFFFFF)),
             DE, ["undecodable", "input_t"]),
        Case("wrong_type_joint", "JOINT_CMD", "-", rawcmd("JOINT_CMD", corrupt(scene(S.PAUSE))), DE,
             ["undecodable", "joint_cmd_t"]),
        Case("empty_payload_input", "INPUT", "-", rawcmd("INPUT", lambda c: b""), DE, ["undecodable", "input_t"]),
        Case("trailing_bytes_body", "BODY_CMD", "REMOVE",
             rawcmd("BODY_CMD", lambda c: corrupt(body(B.REMOVE, MISSING))(c) + b"\x00\x01"), DE,
             ["undecodable", "body_cmd_t"]),
    ]
    ids = [x.id for x in c]
    assert len(ids) == len(set(ids)), "case ids repeat"
    return c


def after_client_id_plus_op(c):
    """The string length field after client_id, request_id and op: the path of a scene_cmd_t."""
    return after_client_id(c) + 8 + 1


def _with_client_id(msg, client_id):
    msg.client_id, msg.request_id = client_id, RAW_REQUEST_ID
    return msg.encode()


