"""The viewer's triangle meshes and heightfields on the WebSocket, without a
server or a browser (docs/viewer.md, "Large surfaces"): the bridge reads
a snapshot's surfaces, refuses a malformed or oversize one with its reason,
and packs the others as float32 and uint32 that the page's decoder
(static/surface_data.js, run in Node) turns back into the same values, and
itself refuses when the bytes and the counts disagree. The page's decoder
tests skip without Node."""
import base64
import json
import shutil
import subprocess

import numpy as np
import pytest

from contactsim.viewer.catalog import catalog_from_snapshot
from contactsim.viewer.connection import catalog_message
from contactsim.viewer.protowire import FIXED64, LENGTH, VARINT, field, varint_bytes
from contactsim.viewer.server import STATIC_DIR
from contactsim.viewer.surface_payload import MAX_HEIGHT_SAMPLES, MAX_MESH_TRIANGLES, pack, unpack

HEIGHTFIELD, MESH = 7, 6   # Shape.Type of service/proto/snapshot.proto


def heightfield(rows, cols, heights, spacing=(0.5, 0.25)):
    """A Shape message on the wire (field numbers: catalog.py _SHAPE)."""
    return (field(1, VARINT, HEIGHTFIELD) + field(11, VARINT, rows) + field(12, VARINT, cols)
            + field(13, LENGTH, np.asarray(heights, "<f8").tobytes())
            + field(14, FIXED64, spacing[0]) + field(15, FIXED64, spacing[1]))


def mesh(vertices, indices):
    packed = b"".join(varint_bytes(int(i) & (1 << 64) - 1) for i in np.ravel(indices))
    return (field(1, VARINT, MESH) + field(9, LENGTH, np.asarray(vertices, "<f8").tobytes())
            + field(10, LENGTH, packed))


def snapshot(*shapes):
    """A Snapshot message of static bodies 1, 2, ... of these shapes."""
    bodies = b"".join(field(7, LENGTH, field(1, VARINT, i + 1) + field(2, LENGTH, b"s%d" % (i + 1))
                            + field(3, LENGTH, s) + field(6, VARINT, 1)) for i, s in enumerate(shapes))
    return field(2, VARINT, 3) + bodies


def shapes_of(data):
    return [b["shape"] for b in catalog_from_snapshot(data)["bodies"]]


TETRA = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
TETRA_TRIANGLES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


# Verifies that the catalog message carries a mesh's vertices and triangles
# and a heightfield's heights as little-endian float32 and uint32 that
# decode to the snapshot's values (float32 of them), and that the rest of
# the shape stays JSON.
def test_surfaces_are_packed_and_unpack_to_the_snapshots_values():
    rng = np.random.default_rng(4)
    heights = rng.uniform(-3, 3, (7, 5))
    vertices = rng.uniform(-2, 2, (40, 3))
    triangles = rng.integers(0, 40, (60, 3))
    message = json.loads(catalog_message(catalog_from_snapshot(
        snapshot(heightfield(7, 5, heights), mesh(vertices, triangles)))))
    field_shape, mesh_shape = (b["shape"] for b in message["bodies"])
    assert {k: field_shape[k] for k in ("kind", "rows", "cols", "spacing")} == {
        "kind": "heightfield", "rows": 7, "cols": 5, "spacing": [0.5, 0.25]}
    assert field_shape["heights"]["dtype"] == "float32" and field_shape["heights"]["count"] == 35
    np.testing.assert_array_equal(unpack(field_shape["heights"]), heights.ravel().astype(np.float32))
    np.testing.assert_array_equal(unpack(mesh_shape["vertices"]), vertices.ravel().astype(np.float32))
    np.testing.assert_array_equal(unpack(mesh_shape["triangles"]), triangles.ravel())


# Verifies that a surface the page cannot draw becomes {kind, error} in the
# catalog, naming what is wrong, while the bodies beside it are read: each
# malformation on purpose, and the server's own limits (2^24 samples,
# 2^20 triangles) exceeded by one.
@pytest.mark.parametrize("shape, reason", [
    (heightfield(3, 4, np.zeros(10)), "10 heights for 3 x 4 samples"),
    (heightfield(1, 4, np.zeros(4)), "1 x 4 samples: at least 2 x 2 are needed"),
    (heightfield(4097, 4096, np.zeros(4)), "4097 x 4096 samples: more than the %d" % MAX_HEIGHT_SAMPLES),
    (heightfield(2, 2, [0, 1, np.nan, 0]), "a height is not finite"),
    (heightfield(2, 2, np.zeros(4), spacing=(0.5, 0.0)), "spacing [0.5, 0.0]"),
    (mesh(TETRA, [[0, 1, 4]]), "index 4 out of range for 4 vertices"),
    (mesh(TETRA, [[0, 1, -1]]), "index -1 out of range for 4 vertices"),
    (mesh(TETRA, [0, 1, 2, 3]), "12 vertex coordinates and 4 indices"),
    (mesh(TETRA, []), "no triangles"),
    (mesh([[0, 0, np.inf], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]), "a vertex is not finite"),
], ids=["heights-count", "one-row", "oversize-grid", "nan-height", "zero-spacing", "index-past-end",
        "negative-index", "partial-triangle", "no-triangles", "inf-vertex"])
def test_malformed_surfaces_are_refused_with_their_reason(shape, reason):
    kind = "heightfield" if shape[1] == HEIGHTFIELD else "mesh"
    refused, kept = shapes_of(snapshot(shape, heightfield(2, 2, np.zeros(4))))
    assert set(refused) == {"kind", "error"} and refused["kind"] == kind
    assert refused["error"].startswith(kind + " refused: ") and reason in refused["error"]
    assert kept["kind"] == "heightfield" and "error" not in kept
    body = json.loads(catalog_message(catalog_from_snapshot(snapshot(shape))))["bodies"][0]
    assert body["shape"] == refused   # sent as it is: the page draws a marker and shows the reason


# Verifies that a mesh one triangle over the server's limit is refused
# (its indices all 0: a million varints of one byte each).
def test_a_mesh_over_the_triangle_limit_is_refused():
    data = snapshot(field(1, VARINT, MESH) + field(9, LENGTH, TETRA.astype("<f8").tobytes())
                    + field(10, LENGTH, bytes(3 * (MAX_MESH_TRIANGLES + 1))))
    (shape,) = shapes_of(data)
    assert shape == {"kind": "mesh", "error": "mesh refused: %d triangles: more than the %d a mesh may have" % (
        MAX_MESH_TRIANGLES + 1, MAX_MESH_TRIANGLES)}


def run_page_decoder(shapes):
    """decodeSurfaces of static/surface_data.js on bodies of these shapes, in
    Node: [errors, [{vertices, triangles} | {heights} as lists]]."""
    node = shutil.which("node")
    if node is None:
        pytest.skip("node is not installed")
    script = ("import { decodeSurfaces } from '%s/surface_data.js';"
              "const bodies = JSON.parse(require_stdin());"
              "const errors = decodeSurfaces(bodies);"
              "const out = bodies.map((b) => b.shape.data ? Object.fromEntries("
              "  Object.entries(b.shape.data).map(([k, v]) => [k, Array.from(v)])) : null);"
              "console.log(JSON.stringify([errors, out]));" % STATIC_DIR)
    script = script.replace("require_stdin()", "(await import('node:fs')).readFileSync(0, 'utf8')")
    bodies = [{"id": i + 1, "name": "", "shape": s} for i, s in enumerate(shapes)]
    run = subprocess.run([node, "--input-type=module", "-e", script], input=json.dumps(bodies),
                         capture_output=True, text=True, timeout=30)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


def _b64(raw):
    return base64.b64encode(raw).decode("ascii")


# Verifies that the page decodes packed surfaces into the values sent, and
# refuses, naming the body and the reason, a field whose bytes do not match
# its count, of another dtype, not base64, heights that are not rows x cols,
# and a triangle index past the vertices; a refused surface has no data (a
# marker is drawn) and does not stop the others.
def test_the_page_decodes_surfaces_and_refuses_malformed_ones():
    heights = np.array([0.5, -1.25, 2.0, 3.5], dtype=np.float32)
    good_field = {"kind": "heightfield", "rows": 2, "cols": 2, "spacing": [1, 1], "heights": pack(heights, "float32")}
    good_mesh = {"kind": "mesh", "vertices": pack(TETRA, "float32"), "triangles": pack(TETRA_TRIANGLES, "uint32")}
    short = dict(pack(heights, "float32"), count=5)
    bad = [
        dict(good_field, heights=short),
        dict(good_field, heights=pack(heights, "uint32")),
        dict(good_field, heights={"dtype": "float32", "count": 4, "base64": "!!not base64!!"}),
        dict(good_field, rows=3),
        dict(good_mesh, triangles=pack([0, 1, 4], "uint32")),
        {"kind": "heightfield", "error": "heightfield refused: 10 heights for 3 x 4 samples"},
    ]
    errors, data = run_page_decoder([good_field, good_mesh, *bad])
    assert data[0] == {"heights": heights.tolist()}
    assert data[1] == {"vertices": TETRA.ravel().tolist(), "triangles": TETRA_TRIANGLES.ravel().tolist()}
    assert data[2:] == [None] * len(bad)
    assert errors == [
        "body 3: heightfield refused: 16 bytes for 5 float32 values",
        "body 4: heightfield refused: expected float32 values, got uint32",
        "body 5: heightfield refused: float32 values: not base64",
        "body 6: heightfield refused: 4 heights for 3 x 2 samples",
        "body 7: mesh refused: index 4 out of range for 4 vertices",
        "body 8: heightfield refused: 10 heights for 3 x 4 samples",
    ]
