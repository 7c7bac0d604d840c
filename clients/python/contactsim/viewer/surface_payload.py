"""Triangle meshes and heightfields in the catalog: the checks a surface
passes before the page draws it, and its form on the WebSocket.

A 1,025 x 1,025 heightfield written as JSON numbers is 22 MB of text that
takes 0.4 s to write and 0.15 s to parse; its heights as little-endian
float32, base64 in the same JSON message, are 5.6 MB that the page decodes
straight into the typed arrays of a three.js BufferGeometry (docs/viewer.md,
"Large surfaces"). The page draws float32 anyway, so nothing it shows is lost.

The limits are the server's: a surface past them cannot come from a world
the server built, only from a damaged or foreign snapshot file.
"""
import base64

import numpy as np

MAX_HEIGHT_SAMPLES = 1 << 24   # kMaxHeightSamples, service/collision/height_field.h
MAX_MESH_TRIANGLES = 1 << 20   # kMaxMeshTriangles, service/collision/triangle_mesh.h
MAX_MESH_VERTICES = 3 * MAX_MESH_TRIANGLES   # more than three a triangle are vertices no triangle uses
DTYPES = {"float32": "<f4", "uint32": "<u4"}
SURFACE_KINDS = ("mesh", "heightfield")
_PACKED = {"mesh": ("vertices", "triangles"), "heightfield": ("heights",)}
_DTYPE_OF = {"vertices": "float32", "triangles": "uint32", "heights": "float32"}


def _heightfield_error(shape):
    rows, cols, heights = shape["rows"], shape["cols"], np.asarray(shape["heights"])
    if rows < 2 or cols < 2:
        return "%d x %d samples: at least 2 x 2 are needed" % (rows, cols)
    if rows * cols > MAX_HEIGHT_SAMPLES:
        return "%d x %d samples: more than the %d a heightfield may have" % (rows, cols, MAX_HEIGHT_SAMPLES)
    if heights.size != rows * cols:
        return "%d heights for %d x %d samples" % (heights.size, rows, cols)
    if not np.all(np.isfinite(heights)):
        return "a height is not finite"
    if not all(np.isfinite(s) and s > 0 for s in shape["spacing"]):
        return "spacing %s: each must be finite and > 0" % (shape["spacing"],)
    return None


def _mesh_error(shape):
    vertices, triangles = np.asarray(shape["vertices"]), np.asarray(shape["triangles"])
    if vertices.size % 3 or triangles.size % 3:
        return "%d vertex coordinates and %d indices: each must be three a vertex or triangle" % (
            vertices.size, triangles.size)
    if triangles.size // 3 > MAX_MESH_TRIANGLES:
        return "%d triangles: more than the %d a mesh may have" % (triangles.size // 3, MAX_MESH_TRIANGLES)
    if vertices.size // 3 > MAX_MESH_VERTICES:
        return "%d vertices: more than the %d a mesh may have" % (vertices.size // 3, MAX_MESH_VERTICES)
    if triangles.size == 0:
        return "no triangles"
    if triangles.min() < 0 or triangles.max() >= vertices.size // 3:
        return "index %d out of range for %d vertices" % (
            triangles.min() if triangles.min() < 0 else triangles.max(), vertices.size // 3)
    if not np.all(np.isfinite(vertices)):
        return "a vertex is not finite"
    return None


def surface_error(shape):
    """Why the page cannot draw a catalog shape of kind mesh or heightfield
    (a message naming the count or value), or None when it can."""
    return _mesh_error(shape) if shape["kind"] == "mesh" else _heightfield_error(shape)


def pack(values, dtype):
    """{"dtype", "count", "base64"}: values as little-endian `dtype`."""
    a = np.ascontiguousarray(values, dtype=DTYPES[dtype])
    return {"dtype": dtype, "count": int(a.size), "base64": base64.b64encode(a.tobytes()).decode("ascii")}


def unpack(field):
    """The numpy array of a packed field; ValueError when its bytes and count disagree."""
    data = base64.b64decode(field["base64"], validate=True)
    size = np.dtype(DTYPES[field["dtype"]]).itemsize
    if len(data) != field["count"] * size:
        raise ValueError("%d bytes for %d values of %s" % (len(data), field["count"], field["dtype"]))
    return np.frombuffer(data, dtype=DTYPES[field["dtype"]])


def page_shape(shape):
    """A catalog shape as the page receives it: a mesh's vertices and
    triangles and a heightfield's heights packed; any other shape as it is."""
    if shape.get("kind") not in SURFACE_KINDS or "error" in shape:
        return shape
    out = dict(shape)
    for name in _PACKED[shape["kind"]]:
        out[name] = pack(shape[name], _DTYPE_OF[name])
    return out


def shape_summary(shape):
    """A shape without its surface's arrays (what a clicked body's panel shows)."""
    if shape.get("kind") not in SURFACE_KINDS:
        return shape
    return {k: v for k, v in shape.items() if k not in _PACKED[shape["kind"]]}
