// Static triangle meshes and heightfields: one BufferGeometry each, built
// from the typed arrays the catalog's surfaces were decoded into
// (surface_data.js; docs/viewer.md, "catalog"), never instanced (few
// bodies, each its own vertices).
import * as THREE from 'three';

// a mesh's vertices (flat x y z, body frame) and triangles (three indices,
// counter-clockwise seen from the front), as the server stores them
export function meshGeometry(shape) {
  const { vertices, triangles } = shape.data;
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
  g.setIndex(new THREE.BufferAttribute(triangles, 1));
  g.computeVertexNormals();
  return g;
}

// Low to high: water blue, grass green, rock brown, snow white.
const RAMP = [0x2f5d8a, 0x4f8a3c, 0x8a6a45, 0xe8e4da].map((c) => new THREE.Color(c).toArray());

// the ramp's colour at t in [0, 1], written to out[at .. at + 2]
function rampColor(t, out, at) {
  const x = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
  const k = Math.min(Math.floor(x), RAMP.length - 2), f = x - k, a = RAMP[k], b = RAMP[k + 1];
  out[at] = a[0] + f * (b[0] - a[0]); out[at + 1] = a[1] + f * (b[1] - a[1]); out[at + 2] = a[2] + f * (b[2] - a[2]);
}

// A heightfield's grid in its body frame, as service/collision/height_field.h
// lays it out: sample (r, c) at x = (c - (cols - 1) / 2) spacing_x,
// y = (r - (rows - 1) / 2) spacing_y, z = heights[r cols + c]; cell (r, c)
// split along its diagonal from (r, c) to (r + 1, c + 1) into the server's
// two triangles, counter-clockwise seen from +z. Each vertex is coloured by
// its height between the lowest and the highest sample.
export function heightfieldGeometry(shape) {
  const { rows, cols, spacing } = shape, { heights } = shape.data;
  const n = rows * cols;
  const pos = new Float32Array(3 * n), col = new Float32Array(3 * n);
  let lo = Infinity, hi = -Infinity;
  for (const h of heights) { lo = Math.min(lo, h); hi = Math.max(hi, h); }
  const span = hi > lo ? hi - lo : 1;
  for (let r = 0; r < rows; r++) {
    for (let c = 0; c < cols; c++) {
      const i = r * cols + c;
      pos[3 * i] = (c - 0.5 * (cols - 1)) * spacing[0];
      pos[3 * i + 1] = (r - 0.5 * (rows - 1)) * spacing[1];
      pos[3 * i + 2] = heights[i];
      rampColor((heights[i] - lo) / span, col, 3 * i);
    }
  }
  const index = new (n > 65535 ? Uint32Array : Uint16Array)(6 * (rows - 1) * (cols - 1));
  let k = 0;
  for (let r = 0; r + 1 < rows; r++) {
    for (let c = 0; c + 1 < cols; c++) {
      const a = r * cols + c, b = a + 1, d = a + cols, e = d + 1;   // (r, c) (r, c+1) (r+1, c) (r+1, c+1)
      index[k] = a; index[k + 1] = b; index[k + 2] = e;
      index[k + 3] = a; index[k + 4] = e; index[k + 5] = d;
      k += 6;
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(gridNormals(rows, cols, heights, spacing), 3));
  g.setAttribute('color', new THREE.BufferAttribute(col, 3));
  g.setIndex(new THREE.BufferAttribute(index, 1));
  return g;
}

// A grid's vertex normals from its slopes, (-dz/dx, -dz/dy, 1) normalised,
// by central differences (one-sided at the border): the same shading as
// averaging the triangles' normals, at a fraction of three's generic
// computeVertexNormals, which takes half a second for a 1,024 x 1,024 grid.
function gridNormals(rows, cols, heights, spacing) {
  const out = new Float32Array(3 * rows * cols);
  for (let r = 0; r < rows; r++) {
    const r0 = Math.max(r - 1, 0), r1 = Math.min(r + 1, rows - 1);
    for (let c = 0; c < cols; c++) {
      const c0 = Math.max(c - 1, 0), c1 = Math.min(c + 1, cols - 1);
      const gx = (heights[r * cols + c1] - heights[r * cols + c0]) / ((c1 - c0) * spacing[0]);
      const gy = (heights[r1 * cols + c] - heights[r0 * cols + c]) / ((r1 - r0) * spacing[1]);
      const inv = 1 / Math.sqrt(gx * gx + gy * gy + 1), i = 3 * (r * cols + c);
      out[i] = -gx * inv; out[i + 1] = -gy * inv; out[i + 2] = inv;
    }
  }
  return out;
}

// true for the kinds drawn by this file, once decoded (a refused one is a marker)
export const isSurface = (shape) => !!shape && (shape.kind === 'mesh' || shape.kind === 'heightfield') && !!shape.data;

// the solid material of a surface: a heightfield takes its vertices' colours;
// both are seen from below too (a mesh may be open, a terrain looked under)
export function surfaceMaterial(shape, color) {
  return shape.kind === 'heightfield'
    ? new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide })
    : new THREE.MeshLambertMaterial({ color, side: THREE.DoubleSide, flatShading: true });
}

export function surfaceGeometry(shape) {
  return shape.kind === 'heightfield' ? heightfieldGeometry(shape) : meshGeometry(shape);
}
