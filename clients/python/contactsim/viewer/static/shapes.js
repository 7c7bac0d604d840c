// One geometry per kind of shape, unit-sized where a scale can size it, so
// that every body of a kind shares one InstancedMesh (a 1,000-body scene is
// a handful of draw calls). Capsules and hulls cannot be scaled into one
// another: each distinct size or hull gets its own instanced group.
import * as THREE from 'three';
import { isSurface, surfaceGeometry } from './surfaces.js';

const MARKER_RADIUS = 0.05;  // m, bodies whose shape is unknown (no snapshot, or a replay without one)

// Triangles per sphere, by how many spheres there are: a software renderer
// (headless chromium, a laptop without a GPU) draws 1,000 coarse spheres
// several times faster than 1,000 fine ones, and at that count each is small on screen.
const sphereDetail = (count) => (count > 300 ? [10, 6] : [20, 14]);

// {key, scale, make(count)} of a catalog shape; the key groups bodies into one InstancedMesh
export function shapeGroup(shape) {
  switch (shape && shape.kind) {
    case 'sphere':
      return { key: 'sphere', scale: [shape.radius, shape.radius, shape.radius],
               make: (count) => new THREE.SphereGeometry(1, ...sphereDetail(count)) };
    case 'box': {
      const h = shape.half_extents;
      return { key: 'box', scale: [2 * h[0], 2 * h[1], 2 * h[2]], make: () => new THREE.BoxGeometry(1, 1, 1) };
    }
    case 'capsule':
      return { key: `capsule:${shape.radius}:${shape.half_length}`, scale: [1, 1, 1],
               make: () => capsule(shape.radius, shape.half_length) };
    case 'convex':
      return { key: `convex:${shape.vertices.join(',')}`, scale: [1, 1, 1], make: () => hull(shape) };
    default:
      return { key: 'marker', scale: [MARKER_RADIUS, MARKER_RADIUS, MARKER_RADIUS],
               make: () => new THREE.IcosahedronGeometry(1, 1) };
  }
}

// three's capsule runs along y; ours along the body's z axis
function capsule(radius, halfLength) {
  const g = new THREE.CapsuleGeometry(radius, 2 * halfLength, 6, 16);
  g.rotateX(Math.PI / 2);
  return g;
}

// the hull's faces (vertex loops, counter-clockwise from outside) as triangle fans
function hull(shape) {
  const v = shape.vertices, pos = [];
  for (const face of shape.faces) {
    for (let i = 1; i + 1 < face.length; i++) {
      for (const k of [face[0], face[i], face[i + 1]]) pos.push(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  g.computeVertexNormals();
  return g;
}

// a plane {p : n.p = offset} as a large square and a grid, not instanced (static, few)
export function planeObject(shape, size) {
  const group = new THREE.Group();
  const square = new THREE.Mesh(new THREE.PlaneGeometry(size, size),
    new THREE.MeshLambertMaterial({ color: 0x3a3f47, side: THREE.DoubleSide }));
  const grid = new THREE.GridHelper(size, Math.round(size), 0x555b66, 0x444a52);
  grid.rotateX(Math.PI / 2);   // GridHelper lies in x-z; the square in x-y
  grid.position.z = 0.001;
  group.add(square, grid);
  const n = new THREE.Vector3(...shape.normal).normalize();
  group.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), n);
  group.position.copy(n.multiplyScalar(shape.offset));
  return group;
}

// A body's collision shape as one object at its real size, for the bodies
// not drawn instanced (compounds, meshes, heightfields, and the links of
// robot models, whose visuals they may replace or overlay): a compound's
// children (hulls, spheres, boxes, capsules) posed in the body frame.
export function collisionObject(shape, material) {
  const group = new THREE.Group();
  const parts = shape && shape.kind === 'compound' ? shape.children
    : [{ shape, position: [0, 0, 0], orientation: [1, 0, 0, 0] }];
  for (const part of parts) {
    let geometry;
    if (isSurface(part.shape)) {
      geometry = surfaceGeometry(part.shape);
    } else {
      const g = shapeGroup(part.shape);
      geometry = g.make(1);
      geometry.scale(...g.scale);
    }
    const mesh = new THREE.Mesh(geometry, material);
    const q = part.orientation;
    mesh.position.set(...part.position);
    mesh.quaternion.set(q[1], q[2], q[3], q[0]);   // ours (w, x, y, z)
    group.add(mesh);
  }
  return group;
}
