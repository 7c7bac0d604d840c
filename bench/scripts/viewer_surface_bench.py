"""Bytes and times of large triangle meshes and heightfields on the viewer's
WebSocket (docs/viewer.md, "Large surfaces"; BENCHMARKS.md, "Viewer").

    .venv/bin/python bench/scripts/viewer_surface_bench.py [--repeat 5]

For heightfields of 257 x 257, 513 x 513 and 1,025 x 1,025 samples and a
mesh of 100,000 triangles, each one body of a snapshot written here in the
server's wire format (service/proto/snapshot.proto), it measures the bridge
reading the snapshot into its catalog, building the catalog message and the
message's size, and V8 (Node, the engine of chromium) parsing it into the
typed arrays a BufferGeometry takes: once as the bridge sends it (binary
arrays, base64 in the JSON: surface_payload.py, static/surface_data.js) and
once with the arrays as JSON numbers, the form it replaced. Medians of
--repeat runs; no server or browser needed, Node is.
"""
import argparse
import json
import statistics
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "clients" / "python"))
from contactsim.viewer.catalog import catalog_from_snapshot  # noqa: E402
from contactsim.viewer.connection import catalog_message  # noqa: E402
from contactsim.viewer.protowire import (FIXED64, LENGTH, VARINT, field, ints, varint_array,  # noqa: E402
                                         varint_bytes)

SURFACE_DATA = REPO / "clients" / "python" / "contactsim" / "viewer" / "static" / "surface_data.js"

# V8's side: JSON.parse of the message, then typed arrays as the page makes them
PARSE_JS = """
import { readFileSync } from 'node:fs';
import { decodeSurfaces } from '%s';
const [binary, numbers, repeat] = [readFileSync(process.argv[2], 'utf8'), readFileSync(process.argv[3], 'utf8'),
                                   Number(process.argv[4])];
function fromNumbers(m) {   // the earlier page: Float32BufferAttribute / setIndex over plain arrays
  for (const b of m.bodies) {
    const s = b.shape;
    if (s.kind === 'heightfield') new Float32Array(s.heights);
    if (s.kind === 'mesh') { new Float32Array(s.vertices); new Uint32Array(s.triangles); }
  }
}
function median(f) {
  const t = [];
  for (let k = 0; k < repeat; k++) { const t0 = performance.now(); f(); t.push(performance.now() - t0); }
  return t.sort((a, b) => a - b)[Math.floor(repeat / 2)];
}
const errors = [];
const tb = median(() => { errors.push(...decodeSurfaces(JSON.parse(binary).bodies)); });
const tn = median(() => fromNumbers(JSON.parse(numbers)));
if (errors.length) throw new Error(errors[0]);
console.log(JSON.stringify([tb, tn]));
"""


def heightfield_shape(rows, cols, spacing=0.05):
    """A Shape message of a rolling terrain (rows x cols samples)."""
    c, r = np.meshgrid(np.arange(cols), np.arange(rows))
    h = 0.5 * np.sin(c / 17.0) * np.cos(r / 23.0)
    return (field(1, VARINT, 7) + field(11, VARINT, rows) + field(12, VARINT, cols)
            + field(13, LENGTH, h.astype("<f8").tobytes()) + field(14, FIXED64, spacing) + field(15, FIXED64, spacing))


def mesh_grid(rows=201, cols=251):
    """(vertices (n, 3), triangles (m, 3)) of a wavy sheet: 200 x 250 cells, 100,000 triangles."""
    x, y = np.meshgrid(np.arange(cols) * 0.1, np.arange(rows) * 0.1)
    v = np.stack([x, y, 0.2 * np.sin(x) * np.cos(y)], -1).reshape(-1, 3)
    a = (np.arange(rows - 1)[:, None] * cols + np.arange(cols - 1)[None, :]).ravel()
    return v, np.stack([a, a + 1, a + cols + 1, a, a + cols + 1, a + cols], -1).reshape(-1, 3)


def mesh_shape():
    v, t = mesh_grid()
    indices = b"".join(varint_bytes(int(i)) for i in t.ravel())
    return field(1, VARINT, 6) + field(9, LENGTH, v.astype("<f8").tobytes()) + field(10, LENGTH, indices), indices


def snapshot(shape):
    """A Snapshot message of one static body of `shape` (field numbers: catalog.py)."""
    body = field(1, VARINT, 1) + field(3, LENGTH, shape) + field(6, VARINT, 1)
    return field(2, VARINT, 1) + field(7, LENGTH, body)


def median_ms(f, repeat):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1e3, out


def numbers_message(catalog):
    """The catalog message with the surfaces' arrays as JSON numbers (the earlier form)."""
    bodies = [{**b, "shape": {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in b["shape"].items()}}
              for b in catalog["bodies"]]
    return json.dumps({"type": "catalog", **catalog, "bodies": bodies})


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    mesh, indices = mesh_shape()
    cases = [("heightfield %s x %s" % (f"{n:,}", f"{n:,}"), heightfield_shape(n, n)) for n in (257, 513, 1025)]
    cases.append(("mesh 100,000 triangles", mesh))
    with tempfile.TemporaryDirectory() as tmp:
        script = Path(tmp) / "parse.mjs"
        script.write_text(PARSE_JS % SURFACE_DATA.as_uri())
        print("| surface | snapshot | snapshot -> catalog | message: binary / numbers | build: binary / numbers"
              " | V8 parse: binary / numbers |")
        print("|---|---:|---:|---:|---:|---:|")
        for name, shape in cases:
            data = snapshot(shape)
            t_read, catalog = median_ms(lambda: catalog_from_snapshot(data), a.repeat)
            t_bin, binary = median_ms(lambda: catalog_message(catalog), a.repeat)
            t_num, numbers = median_ms(lambda: numbers_message(catalog), a.repeat)
            (Path(tmp) / "b.json").write_text(binary)
            (Path(tmp) / "n.json").write_text(numbers)
            run = subprocess.run(["node", str(script), str(Path(tmp) / "b.json"), str(Path(tmp) / "n.json"),
                                  str(a.repeat)], capture_output=True, text=True, check=True)
            p_bin, p_num = json.loads(run.stdout)
            print("| %s | %.1f MB | %.1f ms | %.1f / %.1f MB | %.1f / %.1f ms | %.1f / %.1f ms |" % (
                name, len(data) / 1e6, t_read, len(binary) / 1e6, len(numbers) / 1e6, t_bin, t_num, p_bin, p_num))
    t_vec, _ = median_ms(lambda: varint_array(indices), a.repeat)
    t_one, _ = median_ms(lambda: ints(LENGTH, indices), a.repeat)
    print("\nthe mesh's 300,000 packed indices: %.1f ms with numpy, %.1f ms one varint at a time" % (t_vec, t_one))


if __name__ == "__main__":
    main()
