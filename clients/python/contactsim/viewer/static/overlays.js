// Contact points with their normals, and joints as lines, drawn over the bodies.
import * as THREE from 'three';
import { CONTACT_WIDTH } from './socket.js';

// a LineSegments or Points whose buffer grows to the largest count seen
export function growable(kind, color, extra = {}) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3), 3));
  g.setDrawRange(0, 0);
  const obj = kind === 'points'
    ? new THREE.Points(g, new THREE.PointsMaterial({ color, size: 5, sizeAttenuation: false, ...extra }))
    : new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color, ...extra }));
  obj.frustumCulled = false;
  obj.renderOrder = 1;
  return obj;
}

// writes count vertices' x y z into an attribute (position, or color), growing it when short
export function fill(obj, count, write, name = 'position') {
  let attr = obj.geometry.getAttribute(name);
  if (!attr || attr.count < count) {
    attr = new THREE.BufferAttribute(new Float32Array(3 * Math.max(count, 2 * (attr ? attr.count : 1))), 3);
    obj.geometry.setAttribute(name, attr);
  }
  write(attr.array);
  attr.needsUpdate = true;
  obj.geometry.setDrawRange(0, count);
}

export class Contacts {
  constructor(scene) {
    this.points = growable('points', 0xff4d4d, { depthTest: false });
    this.normals = growable('lines', 0xffe14d, { depthTest: false });
    this.normalLength = 0.1;   // m; main.js sizes it to the scene
    this.count = 0;
    this.changed = false;   // a new frame to draw even when no poses came with it
    scene.add(this.points, this.normals);
  }

  apply(frame) {
    const r = frame.rows, n = frame.n, L = this.normalLength;
    this.count = n;
    this.changed = true;
    fill(this.points, n, (a) => { for (let i = 0; i < n; i++) a.set(r.subarray(i * CONTACT_WIDTH, i * CONTACT_WIDTH + 3), 3 * i); });
    fill(this.normals, 2 * n, (a) => {
      for (let i = 0; i < n; i++) {
        const o = i * CONTACT_WIDTH;
        for (let k = 0; k < 3; k++) { a[6 * i + k] = r[o + k]; a[6 * i + 3 + k] = r[o + k] + L * r[o + 3 + k]; }
      }
    });
  }

  setVisible(v) { this.points.visible = this.normals.visible = v; }
}

// each joint: A's centre -> its anchor -> B's anchor -> B's centre (world anchor for body_b 0)
export class Joints {
  constructor(scene) {
    this.lines = growable('lines', 0x4dd2ff, { depthTest: false });
    this.joints = [];
    scene.add(this.lines);
  }

  setCatalog(joints) { this.joints = joints || []; }

  update(bodies) {
    const pts = [];
    for (const j of this.joints) {
      const a = bodies.pose(j.body_a);
      if (!a) continue;
      const pa = new THREE.Vector3(...j.anchor_a).applyQuaternion(a.q).add(a.p);
      const b = j.body_b ? bodies.pose(j.body_b) : null;
      const pb = b ? new THREE.Vector3(...j.anchor_b).applyQuaternion(b.q).add(b.p) : new THREE.Vector3(...j.anchor_b);
      pts.push(a.p, pa, pa, pb);
      if (b) pts.push(pb, b.p);
    }
    fill(this.lines, pts.length, (arr) => pts.forEach((p, i) => p.toArray(arr, 3 * i)));
  }
}
