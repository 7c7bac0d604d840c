"""What STATE does not carry: each body's shape, name and mass, the joints,
the range sensors and the robot models, read from a snapshot file of the
server (service/proto/snapshot.proto) into plain dicts the page can draw
(docs/viewer.md, "catalog"). A mesh's vertices and triangles and a
heightfield's heights are numpy arrays (float64, int64), packed for the
page by surface_payload.py; a surface that fails its checks there is
{"kind", "error"} instead."""
import numpy as np

from .model_catalog import MODEL, model_entry
from .protowire import parse
from .surface_payload import surface_error

SHAPE_KINDS = {0: "sphere", 1: "box", 2: "capsule", 3: "convex", 4: "plane", 5: "compound", 6: "mesh",
               7: "heightfield"}
MOTIONS = {0: "dynamic", 1: "static", 2: "kinematic"}
JOINT_KINDS = {0: "distance", 1: "ball", 2: "hinge", 3: "fixed", 4: "prismatic"}

_NONE = np.zeros(0)
_FACE = {1: ("normal", "double", True), 3: ("vertices", "int", True)}
_HULL = {1: ("vertices", "double", True), 2: ("faces", _FACE, True)}
_SHAPE = {1: ("type", "int", False), 2: ("radius", "double", False), 3: ("half_extents", "double", True),
          4: ("half_length", "double", False), 5: ("plane_normal", "double", True),
          6: ("plane_offset", "double", False), 7: ("hull", _HULL, False),
          9: ("mesh_vertices", "double_array", True), 10: ("mesh_indices", "int_array", True),
          11: ("height_rows", "int", False), 12: ("height_cols", "int", False),
          13: ("heights", "double_array", True),
          14: ("height_spacing_x", "double", False), 15: ("height_spacing_y", "double", False)}
_CHILD = {1: ("shape", _SHAPE, False), 2: ("position", "double", True), 3: ("orientation", "double", True)}
_SHAPE[8] = ("children", _CHILD, True)   # a compound's shapes (never compounds themselves)
_BODY = {1: ("id", "int", False), 2: ("name", "string", False), 3: ("shape", _SHAPE, False),
         6: ("motion", "int", False), 7: ("mass", "double", False), 11: ("x", "double", True),
         12: ("q", "double", True)}
_ACTUATOR = {1: ("torque", "double", False), 2: ("target_position", "double", False),
             3: ("target_velocity", "double", False), 4: ("kp", "double", False), 5: ("kd", "double", False)}
_JOINT = {1: ("id", "int", False), 2: ("kind", "int", False), 3: ("body_a", "int", False),
          4: ("body_b", "int", False), 5: ("anchor_a", "double", True), 6: ("anchor_b", "double", True),
          7: ("axis_a", "double", True), 9: ("rest", "double", True), 11: ("limited", "bool", False),
          12: ("lower", "double", False), 13: ("upper", "double", False), 21: ("actuator", _ACTUATOR, False)}
_RANGE = {1: ("name", "string", False), 2: ("body", "int", False), 3: ("origin", "double", True),
          5: ("max_distance", "double", False)}
_SNAPSHOT = {2: ("step", "int", False), 3: ("time", "double", False), 7: ("bodies", _BODY, True), 9: ("contact_method", "string", False),
             14: ("joints", _JOINT, True), 17: ("range_sensors", _RANGE, True), 40: ("models", MODEL, True)}


def _shape(s):
    kind = SHAPE_KINDS.get(s.get("type", 0), "unknown")
    out = {"kind": kind}
    if kind in ("sphere", "capsule"):
        out["radius"] = s.get("radius", 0.0)
    if kind == "capsule":
        out["half_length"] = s.get("half_length", 0.0)
    if kind == "box":
        out["half_extents"] = s.get("half_extents", [0.0, 0.0, 0.0])
    if kind == "plane":
        out["normal"] = s.get("plane_normal", [0.0, 0.0, 1.0])
        out["offset"] = s.get("plane_offset", 0.0)
    if kind == "convex":
        hull = s.get("hull", {})
        out["vertices"] = hull.get("vertices", [])
        out["faces"] = [f.get("vertices", []) for f in hull.get("faces", [])]
    if kind == "mesh":
        # body frame; triangles counter-clockwise seen from the front
        out["vertices"] = s.get("mesh_vertices", _NONE)
        out["triangles"] = s.get("mesh_indices", _NONE)
    if kind == "heightfield":
        # heights row-major, rows along body y, centred on the body origin
        # (service/collision/height_field.h); each cell two triangles
        out["rows"] = s.get("height_rows", 0)
        out["cols"] = s.get("height_cols", 0)
        out["heights"] = s.get("heights", _NONE)
        out["spacing"] = [s.get("height_spacing_x", 0.0), s.get("height_spacing_y", 0.0)]
    if kind in ("mesh", "heightfield"):
        error = surface_error(out)
        if error is not None:   # drawn as a marker; the page shows why
            return {"kind": kind, "error": "%s refused: %s" % (kind, error)}
    if kind == "compound":
        out["children"] = [{"shape": _shape(c.get("shape", {})), "position": c.get("position", [0.0] * 3),
                            "orientation": c.get("orientation", [1.0, 0.0, 0.0, 0.0])}
                           for c in s.get("children", [])]
    return out


def _actuator(joint):
    """A joint's standing actuator (docs/actuators.md), or None without one."""
    a = joint.get("actuator")
    if a is None:
        return None
    return {k: a.get(k, 0.0) for k in ("torque", "target_position", "target_velocity", "kp", "kd")}


def catalog_from_snapshot(data):
    """{"step", "time", "bodies": [{id, name, motion, mass, shape, x, q}], "joints":
    [{id, kind, body_a, body_b, anchor_a, anchor_b, axis_a, rest, limited, lower, upper, actuator}],
    "range_sensors": [{name, body, origin, max_distance}], "models": [model_catalog.model_entry]}
    from a snapshot's bytes. Anchors, axes and sensor origins are in the bodies'
    frames (anchor_b in the world's for body_b 0)."""
    snap = parse(data, _SNAPSHOT)
    bodies = [{"id": b.get("id", 0), "name": b.get("name", ""), "motion": MOTIONS.get(b.get("motion", 0), "?"),
               "mass": b.get("mass", 0.0), "shape": _shape(b.get("shape", {})),
               "x": b.get("x", [0.0] * 3), "q": b.get("q", [1.0, 0.0, 0.0, 0.0])} for b in snap.get("bodies", [])]
    joints = [{"id": j.get("id", 0), "kind": JOINT_KINDS.get(j.get("kind", 0), "?"), "body_a": j.get("body_a", 0),
               "body_b": j.get("body_b", 0), "anchor_a": j.get("anchor_a", [0.0] * 3),
               "anchor_b": j.get("anchor_b", [0.0] * 3), "axis_a": j.get("axis_a", [0.0, 0.0, 1.0]),
               "rest": j.get("rest", [1.0, 0.0, 0.0, 0.0]), "limited": j.get("limited", False),
               "lower": j.get("lower", 0.0), "upper": j.get("upper", 0.0), "actuator": _actuator(j)}
              for j in snap.get("joints", [])]
    ranges = [{"name": r.get("name", ""), "body": r.get("body", 0), "origin": r.get("origin", [0.0] * 3),
               "max_distance": r.get("max_distance", 0.0)} for r in snap.get("range_sensors", [])]
    return {"step": snap.get("step", 0), "time": snap.get("time", 0.0), "bodies": bodies, "joints": joints,
            "range_sensors": ranges, "models": [model_entry(m) for m in snap.get("models", [])]}


def read_catalog(path):
    with open(path, "rb") as f:
        return catalog_from_snapshot(f.read())
