"""The LCM wire layout of contactsim's command types, and garbage made from it.

LCM encodes a message as an 8-byte fingerprint, then its fields in
declaration order, big-endian: integers and doubles at their size, a string
as an int32 length that counts the closing NUL and then the bytes, an array
as its elements one after another (a variable dimension is the value of an
earlier integer field). ``layout()`` walks a payload along the type's
.lcm file and names the offset of every length and count field, so that the
garbage below can corrupt exactly those; ``lenient_decode()`` decodes like
lcm-gen's C++ decoders do (every length and count in range, the closing NUL
and trailing bytes not checked), which tells whether a mutated payload is
in fact a well-formed command that some server would apply.

    from lcm_wire import Garbage
    world = dict(bodies={1, 2}, joints={1}, slots=set())  # what the target server holds
    for channel, payload, what in Garbage(seed=1).corpus(3000, world):
        lc.publish(prefix + "_" + channel, payload)

A helper of the tests (test_garbage.py, bad_input_cases.py), which
scripts/soak.py borrows.
"""
import importlib.util
import random
import struct
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LCMTYPES = REPO / "lcmtypes"


def _load_schema():
    """cmake/lcm_schema.py, the one reader of lcmtypes/ (the build's generators use it too)."""
    spec = importlib.util.spec_from_file_location("lcm_schema", REPO / "cmake" / "lcm_schema.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_schema = _load_schema()
PRIMITIVE = {"int8_t": ">b", "byte": ">B", "boolean": ">b", "int16_t": ">h", "int32_t": ">i",
             "int64_t": ">q", "float": ">f", "double": ">d"}
STRUCTS = {name: s.fields for name, s in _schema.parse_folder(LCMTYPES).items()}
# The command channel of each command type (lcmtypes/protocol.toml).
CHANNEL_TYPES = {c.name: c.type for c in _schema.load_protocol(LCMTYPES / "protocol.toml", STRUCTS).channels
                 if c.incoming}

# A SCENE_CMD payload that made the server throw std::length_error (a string
# length field of 0, read as a size of -1): kept as a regression case.
REGRESSION_SCENE_CMD = bytes.fromhex(
    "9efc6968c317985c8000000566757a7a000000007f800000807f00007f7f000000ffff000000007f007f8000007f7f"
    "008000ff008000000000000000000000007f007f0000000000007f00000000ff008000008000000000010000ff00ff"
    "0000000000ff7f000000ff0000")


class Malformed(Exception):
    """The payload does not decode: a length or count out of range, or too few bytes."""


class Span:
    """One field's place in a payload: ``kind`` is "fingerprint", "value",
    "strlen" (the int32 length of a string) or "count" (an integer field
    that is an array's dimension)."""
    __slots__ = ("kind", "path", "offset", "size", "fmt")

    def __init__(self, kind, path, offset, size, fmt=None):
        self.kind, self.path, self.offset, self.size, self.fmt = kind, path, offset, size, fmt

    def __repr__(self):
        return "Span(%s %s @%d+%d)" % (self.kind, self.path, self.offset, self.size)


def _count_fields(fields):
    return {d for _, _, dims in fields for d in dims if not d.isdigit()}


class _Reader:
    def __init__(self, data, spans):
        self.data, self.pos, self.spans = data, 0, spans

    def take(self, n):
        if n < 0 or self.pos + n > len(self.data):
            raise Malformed("needs %d bytes at offset %d of %d" % (n, self.pos, len(self.data)))
        b = self.data[self.pos:self.pos + n]
        self.pos += n
        return b

    def primitive(self, ftype, path, kind="value"):
        fmt = PRIMITIVE[ftype]
        size = struct.calcsize(fmt)
        if self.spans is not None:
            self.spans.append(Span(kind, path, self.pos, size, fmt))
        return struct.unpack(fmt, self.take(size))[0]

    def string(self, path):
        if self.spans is not None:
            self.spans.append(Span("strlen", path, self.pos, 4, ">i"))
        n = struct.unpack(">i", self.take(4))[0]
        if n < 1:  # lcm-gen's decoders read n - 1 bytes: 0 and below are never valid
            raise Malformed("%s: string length %d" % (path, n))
        return self.take(n)[:-1]  # the NUL is not checked (as in lcm-gen's decoders)

    def element(self, ftype, path, counted):
        if ftype == "string":
            return self.string(path)
        if ftype in PRIMITIVE:
            return self.primitive(ftype, path, "count" if counted else "value")
        return self.struct(ftype, path)

    def array(self, ftype, path, dims, values):
        if not dims:
            return self.element(ftype, path, False)
        d = dims[0]
        n = int(d) if d.isdigit() else values[d]
        if n < 0:
            raise Malformed("%s: count %s = %d" % (path, d, n))
        if ftype in PRIMITIVE and n > len(self.data):  # cheap bound before the loop
            raise Malformed("%s: count %s = %d exceeds the payload" % (path, d, n))
        return [self.array(ftype, "%s[%d]" % (path, i), dims[1:], values) for i in range(n)]

    def struct(self, type_name, prefix=""):
        fields = STRUCTS[type_name]
        counts = _count_fields(fields)
        values = {}
        for ftype, name, dims in fields:
            path = prefix + name
            if dims:
                values[name] = self.array(ftype, path, dims, values)
            else:
                values[name] = self.element(ftype, path, name in counts)
        return values


def fingerprint(type_name):
    """The 8-byte fingerprint that begins an encoded message of type_name."""
    import contactsim  # noqa: PLC0415 - the generated classes
    return getattr(contactsim, type_name)._get_packed_fingerprint()


def lenient_decode(type_name, payload):
    """-> (field values, bytes used) as lcm-gen's decoders would read the
    payload (strings as bytes), or raises Malformed."""
    if payload[:8] != fingerprint(type_name):
        raise Malformed("fingerprint of another type")
    r = _Reader(payload, None)
    r.pos = 8
    values = r.struct(type_name)
    return values, r.pos


def layout(type_name, payload):
    """The Spans of a well-formed payload of type_name, fingerprint first."""
    spans = [Span("fingerprint", "", 0, 8)]
    r = _Reader(payload, spans)
    r.pos = 8
    r.struct(type_name)
    if r.pos != len(payload):
        raise Malformed("%d trailing bytes" % (len(payload) - r.pos))
    return spans


# ------------------------------------------------------------------ seeds
def seed_messages(missing_body=123456789, missing_joint=987654321):
    """One valid message of every op of every command type, as (channel,
    message, op name). Body and joint ids are ``missing_*``, which a
    test world does not hold, so that the plain message is refused with
    NOT_FOUND rather than applied; ADD, RESET and the like are world
    changing by nature (see world_changing)."""
    from contactsim import body_cmd_t as B, joint_cmd_t as J, scene_cmd_t as S, input_t as I  # noqa: N817
    from contactsim import model_cmd_t as M  # noqa: N817

    out = []

    def body(op_name, **fields):
        m = B()
        m.client_id, m.request_id, m.op, m.body_id = "garbage-seed", 1, getattr(B, op_name), missing_body
        m.orientation = [1.0, 0.0, 0.0, 0.0]
        for k, v in fields.items():
            setattr(m, k, v)
        out.append(("BODY_CMD", m, "body " + op_name))

    for shape, fields in (("SPHERE", dict(radius=0.1)), ("BOX", dict(half_extents=[0.1, 0.2, 0.3])),
                          ("PLANE", dict(plane_normal=[0.0, 0.0, 1.0], fixed=True)),
                          ("CAPSULE", dict(radius=0.05, half_length=0.2)),
                          ("CONVEX", dict(num_points=5, points=[[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0],
                                                                [0.0, 0.0, 0.1], [0.1, 0.1, 0.1]]))):
        m = B()
        m.client_id, m.request_id, m.op, m.shape = "garbage-seed", 1, B.ADD, getattr(B, shape)
        m.position, m.orientation, m.mass, m.name = [5.0, 5.0, 1.0], [1.0, 0.0, 0.0, 0.0], 1.0, "seed-" + shape.lower()
        m.has_restitution, m.restitution, m.has_friction, m.friction = True, 0.3, True, 0.6
        for k, v in fields.items():
            setattr(m, k, v)
        if shape == "PLANE":
            m.mass = 0.0
        out.append(("BODY_CMD", m, "body ADD " + shape))
    body("REMOVE")
    body("SET_POSE", position=[0.0, 0.0, 1.0], orientation=[0.0, 0.0, 0.0, 1.0])
    body("SET_VELOCITY", linear_velocity=[1.0, 0.0, 0.0], angular_velocity=[0.0, 0.0, 1.0])
    body("APPLY_FORCE", force=[0.0, 0.0, 10.0], torque=[0.0, 1.0, 0.0], duration=0.5)
    body("APPLY_IMPULSE", impulse=[1.0, 0.0, 0.0], has_point=True, point=[0.0, 0.0, 1.0])
    body("SET_MASS", mass=2.0)
    body("SET_MATERIAL", has_restitution=True, restitution=0.4, has_friction=True, friction=0.7)
    body("SET_FILTER", collision_category=2, collision_mask=-1, collision_group=-3)

    def scene(op_name, **fields):
        m = S()
        m.client_id, m.request_id, m.op = "garbage-seed", 1, getattr(S, op_name)
        for k, v in fields.items():
            setattr(m, k, v)
        out.append(("SCENE_CMD", m, "scene " + op_name))

    scene("RESET")
    scene("LOAD_SCENE", path="/nonexistent/garbage-scene.pbtxt")
    scene("SET_GRAVITY", gravity=[0.0, 0.0, -9.81])
    scene("SET_TIMESTEP", dt=1.0 / 240.0)
    scene("SET_METHOD", method="impulse", num_params=2, param_names=["iterations", "restitution_threshold"],
          param_values=["20", "0.1"])
    scene("PAUSE")
    scene("RESUME")
    scene("STEP", steps=3)
    scene("SET_MODE", mode=S.FREE_RUN, real_time_factor=1.0)
    scene("SNAPSHOT", name="garbage_slot")
    scene("RESTORE", name="no_such_slot")
    scene("REWIND", target_step=0)
    scene("REGISTER_CONTROLLER", late_policy=S.LATE_WAIT, late_timeout=0.5)
    scene("RELEASE_CONTROLLER")

    for op_name, fields in (("ADD", dict(kind=J.HINGE, body_a=missing_body, body_b=0, anchor=[0.0, 0.0, 1.0],
                                         has_axis=True, axis=[0.0, 0.0, 1.0], has_limits=True, lower=-1.0,
                                         upper=1.0)),
                            ("ADD", dict(kind=J.DISTANCE, body_a=missing_body, body_b=missing_body + 1,
                                         anchor=[0.0, 0.0, 1.0], has_length=True, length=0.5)),
                            ("REMOVE", dict(joint_id=missing_joint))):
        m = J()
        m.client_id, m.request_id, m.op = "garbage-seed", 1, getattr(J, op_name)
        for k, v in fields.items():
            setattr(m, k, v)
        out.append(("JOINT_CMD", m, "joint " + op_name))

    for op_name, fields in (("LOAD", dict(path="/nonexistent/garbage-model.urdf", orientation=[1.0, 0.0, 0.0, 0.0])),
                            ("LOAD", dict(text="<robot name='garbage'><link name='a'/></robot>", name="seed",
                                          orientation=[1.0, 0.0, 0.0, 0.0])),
                            ("REMOVE", dict(model_id=missing_joint)),
                            ("INFO", dict())):
        m = M()
        m.client_id, m.request_id, m.op = "garbage-seed", 1, getattr(M, op_name)
        m.resolved_size, m.resolved = 0, b""
        for k, v in fields.items():
            setattr(m, k, v)
        out.append(("MODEL_CMD", m, "model " + op_name))

    for n in (0, 1, 3):
        m = I()
        m.client_id, m.request_id, m.step, m.num_bodies = "garbage-seed", 1, 1, n
        m.body_ids = [missing_body + i for i in range(n)]
        m.forces = [[1.0, 2.0, 3.0]] * n
        m.torques = [[0.0, 0.0, 0.5]] * n
        out.append(("INPUT", m, "input %d bodies" % n))

    from contactsim.actuators import JointCommand, encode_joint_command
    from contactsim import actuator_cmd_t as A  # noqa: N817
    for op_name in ("SET", "CLEAR", "STATE"):
        m = A()
        m.client_id, m.request_id, m.op = "garbage-seed", 1, getattr(A, op_name)
        m.joints = encode_joint_command(JointCommand([missing_joint, missing_joint + 1], kp=10.0, target_position=0.5))
        out.append(("ACTUATOR_CMD", m, "actuator " + op_name))
    m = I()
    m.client_id, m.request_id, m.step, m.num_bodies = "garbage-seed", 1, 1, 0
    m.joints = encode_joint_command(JointCommand([missing_joint], torque=1.0))
    out.append(("INPUT", m, "input 1 joint"))
    return out


# ------------------------------------------------------- world changing?
SCENE_INERT_OPS = {6, 10, 11}   # PAUSE, SNAPSHOT, RESTORE (when harmless, below)


def world_changing(type_name, values, world):
    """True when a well-formed command could change the world or the run of
    a paused test server: the garbage corpus leaves such commands out
    (they are not garbage). ``world``: dict with sets ``bodies``,
    ``joints`` and ``slots`` (snapshot slot names)."""
    op = values.get("op")
    if type_name == "body_cmd_t":
        if op == 1:
            return True                                  # ADD
        return 2 <= op <= 9 and values["body_id"] in world["bodies"]
    if type_name == "joint_cmd_t":
        if op == 2:
            return values["joint_id"] in world["joints"]
        if op == 1:
            return values["body_a"] in world["bodies"] and (values["body_b"] == 0 or values["body_b"] in world["bodies"])
        return False
    if type_name == "model_cmd_t":
        return op == 1                                   # LOAD (REMOVE finds no model in a test world)
    if type_name == "scene_cmd_t":
        if op not in range(1, 15):
            return False
        if op not in SCENE_INERT_OPS:
            return True                                  # resets, steps, runs, changes parameters
        if op == 10:
            return bool(values["path"])                  # would write a file somewhere
        if op == 11:
            path = values["path"].decode("utf-8", "replace")
            return (values["name"].decode("utf-8", "replace") in world["slots"]
                    or (bool(path) and Path(path).exists()))
        return False
    if type_name == "actuator_cmd_t":
        return op in (1, 2) and any(j in world["joints"] for j in values["joints"]["joint_ids"])
    if type_name == "input_t":
        return False  # no controller is registered in a garbage test, so every input is refused
    raise ValueError(type_name)


# ---------------------------------------------------------------- garbage
HUGE = (0x7FFFFFFF, -0x80000000, 0x40000000, 1 << 24)


class Garbage:
    """Malformed payloads for every command channel, from a seeded RNG."""

    KINDS = ("random", "truncated", "bitflip", "overwrite", "strlen", "count", "overlong", "wrong_type",
             "spliced")

    def __init__(self, seed=0, seeds=None, client_id="garbage-seed", request_ids=None):
        """``request_ids``: an iterator of request ids, one per payload (a
        replay tells commands apart by client id and request id); None:
        every seed keeps request id 1."""
        self.rng = random.Random(seed)
        self.seeds = seeds if seeds is not None else seed_messages()
        self.client_id = client_id
        self.request_ids = request_ids

    def _pick(self):
        channel, msg, op = self.rng.choice(self.seeds)
        msg.client_id = self.client_id
        msg.request_id = next(self.request_ids) if self.request_ids is not None else 1
        return channel, msg.encode(), op, CHANNEL_TYPES[channel]

    def random(self):
        channel = self.rng.choice(list(CHANNEL_TYPES))
        n = self.rng.choice([0, 1, 7, 8, 9, 16, 64, 200, 1000, self.rng.randrange(2000)])
        body = bytes(self.rng.randrange(256) for _ in range(n))
        if self.rng.random() < 0.5:  # the right fingerprint, then noise
            body = fingerprint(CHANNEL_TYPES[channel]) + body
        return channel, body, "random bytes"

    def truncated(self):
        channel, p, op, _ = self._pick()
        cut = self.rng.randrange(0, len(p))
        return channel, p[:cut], "%s truncated to %d of %d bytes" % (op, cut, len(p))

    def bitflip(self):
        channel, p, op, _ = self._pick()
        b = bytearray(p)
        flips = self.rng.choice([1, 1, 2, 3, 8, 32])
        for _ in range(flips):
            # mostly in the fields, now and then in the fingerprint
            i = self.rng.randrange(0 if self.rng.random() < 0.03 else 8, len(b))
            b[i] ^= 1 << self.rng.randrange(8)
        return channel, bytes(b), "%s with %d bit(s) flipped" % (op, flips)

    def overwrite(self):
        channel, p, op, _ = self._pick()
        b = bytearray(p)
        for _ in range(self.rng.choice([1, 2, 4, 16])):
            i = self.rng.randrange(8, len(b))
            b[i] = self.rng.choice([0x00, 0xFF, 0x7F, 0x80, self.rng.randrange(256)])
        return channel, bytes(b), "%s with bytes overwritten" % op

    def _set_int(self, p, span, value):
        b = bytearray(p)
        b[span.offset:span.offset + span.size] = struct.pack(span.fmt, value)
        return bytes(b)

    def strlen(self):
        channel, p, op, t = self._pick()
        spans = [s for s in layout(t, p) if s.kind == "strlen"]
        s = self.rng.choice(spans)
        old = struct.unpack(">i", p[s.offset:s.offset + 4])[0]
        value = self.rng.choice([0, -1, -5, *HUGE, old + 1, old - 1, old + 1000, len(p), len(p) - s.offset])
        return channel, self._set_int(p, s, value), "%s: %s length %d -> %d" % (op, s.path, old, value)

    def count(self):
        channel, p, op, t = self._pick()
        spans = [s for s in layout(t, p) if s.kind == "count"]
        if not spans:
            return self.strlen()
        s = self.rng.choice(spans)
        old = struct.unpack(s.fmt, p[s.offset:s.offset + s.size])[0]
        value = self.rng.choice([-1, -2, *HUGE, old + 1, old - 1, old * 1000 + 7, 1 << 20])
        return channel, self._set_int(p, s, value), "%s: %s %d -> %d" % (op, s.path, old, value)

    def overlong(self):
        channel, p, op, _ = self._pick()
        n = self.rng.choice([1, 3, 8, 100, 4096, 65536, 200000])
        tail = bytes(self.rng.randrange(256) for _ in range(min(n, 256))) * (n // 256 + 1)
        return channel, p + tail[:n], "%s with %d trailing bytes" % (op, n)

    def wrong_type(self):
        channel, p, op, t = self._pick()
        other = self.rng.choice([c for c in CHANNEL_TYPES if c != channel])
        return other, p, "%s sent on %s" % (op, other)

    def spliced(self):
        c1, p1, op1, _ = self._pick()
        _, p2, op2, _ = self._pick()
        i, j = self.rng.randrange(8, len(p1)), self.rng.randrange(8, len(p2))
        return c1, p1[:i] + p2[j:], "%s spliced with %s" % (op1, op2)

    def one(self, kind):
        return getattr(self, kind)()

    def corpus(self, count, world):
        """``count`` payloads cycling through every kind, plus the regression
        payload: a list of (channel, payload, description). Payloads that
        decode to a world-changing command (world_changing) are left out;
        ``self.left_out`` counts them."""
        out = [("SCENE_CMD", REGRESSION_SCENE_CMD, "regression: SCENE_CMD with string length 0")]
        self.left_out = 0
        i = 0
        while len(out) < count:
            channel, payload, what = self.one(self.KINDS[i % len(self.KINDS)])
            i += 1
            t = CHANNEL_TYPES[channel]
            try:
                values, _ = lenient_decode(t, payload)
            except Malformed:
                values = None
            if values is not None and world_changing(t, values, world):
                self.left_out += 1
                continue
            out.append((channel, payload, what))
        return out
