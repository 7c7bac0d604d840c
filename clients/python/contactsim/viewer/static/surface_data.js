// The arrays of a catalog's triangle meshes and heightfields, which the
// bridge sends as little-endian float32 and uint32, base64 in the catalog's
// JSON (surface_payload.py), decoded straight into the typed arrays that
// three.js BufferGeometry takes. No three.js here, so Node runs it too
// (tests/python/test_viewer_surface_payload.py, bench/scripts/viewer_surface_bench.py).

const ARRAYS = { float32: Float32Array, uint32: Uint32Array };

function bytesOf(text) {
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
  const s = atob(text), out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) out[i] = s.charCodeAt(i);
  return out;
}

// {dtype, count, base64} -> a typed array of `count` values; throws on another dtype or a wrong length
export function unpack(field, dtype) {
  if (!field || field.dtype !== dtype || !Number.isInteger(field.count) || typeof field.base64 !== 'string') {
    throw new Error(`expected ${dtype} values, got ${field && field.dtype}`);
  }
  let bytes;
  try { bytes = bytesOf(field.base64); } catch (e) { throw new Error(`${dtype} values: not base64`); }
  const T = ARRAYS[dtype];
  if (bytes.length !== field.count * T.BYTES_PER_ELEMENT) {
    throw new Error(`${bytes.length} bytes for ${field.count} ${dtype} values`);
  }
  // the decoded bytes start at offset 0 of their own buffer: aligned for any element size
  return new T(bytes.buffer, bytes.byteOffset, field.count);
}

// A catalog surface's arrays, checked as the page uses them: a mesh's
// {vertices: Float32Array, triangles: Uint32Array}, each index below the
// vertex count; a heightfield's {heights: Float32Array} of rows x cols.
// Throws an Error that says what is wrong.
export function decodeSurface(shape) {
  if (shape.kind === 'mesh') {
    const vertices = unpack(shape.vertices, 'float32'), triangles = unpack(shape.triangles, 'uint32');
    if (vertices.length % 3 || triangles.length % 3) {
      throw new Error(`${vertices.length} coordinates and ${triangles.length} indices, not three each`);
    }
    let top = 0;
    for (let i = 0; i < triangles.length; i++) if (triangles[i] > top) top = triangles[i];
    if (triangles.length && top >= vertices.length / 3) {
      throw new Error(`index ${top} out of range for ${vertices.length / 3} vertices`);
    }
    return { vertices, triangles };
  }
  const heights = unpack(shape.heights, 'float32');
  if (!(shape.rows >= 2 && shape.cols >= 2) || heights.length !== shape.rows * shape.cols) {
    throw new Error(`${heights.length} heights for ${shape.rows} x ${shape.cols} samples`);
  }
  return { heights };
}

// Decodes every surface of a catalog's bodies into shape.data once, when
// the catalog arrives (the bodies are laid out again at each change of ids).
// A surface the bridge refused, or that fails here, keeps shape.error and is
// drawn as a marker; returns those errors as "body <id> (<name>): <error>".
export function decodeSurfaces(bodies) {
  const errors = [];
  for (const b of bodies) {
    const s = b.shape;
    if (!s || (s.kind !== 'mesh' && s.kind !== 'heightfield')) continue;
    if (!s.error) {
      try { s.data = decodeSurface(s); } catch (e) { s.error = `${s.kind} refused: ${e.message}`; }
    }
    if (s.error) errors.push(`body ${b.id}${b.name ? ` (${b.name})` : ''}: ${s.error}`);
  }
  return errors;
}
