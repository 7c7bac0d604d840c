// Rays over the bodies: the newest ray cast of any client (green to a hit,
// grey to the farthest point of a miss) and the range sensors' fans (cyan
// to a hit, grey to the range), with a point at each hit and, where the
// reading has one (a ray cast's hits), the surface's normal as a short
// yellow line, as long as a contact's. A sensor's rays
// start at its origin in its body's frame, placed with the body's pose of
// the frame drawn (rays.py says where the bridge finds them).
import * as THREE from 'three';
import { fill, growable } from './overlays.js';
import { RAY_WIDTH } from './socket.js';

const HIT = { 0: new THREE.Color(0x7cfc00), 1: new THREE.Color(0x40e0ff) };
const MISS = new THREE.Color(0x6a6f78);

export class Rays {
  constructor(scene) {
    this.frames = { 0: null, 1: null };   // the newest RAYS frame of each kind
    // white materials: the vertex colours carry hit and miss
    this.lines = growable('lines', 0xffffff, { vertexColors: true, depthTest: false });
    this.hits = growable('points', 0xffffff, { vertexColors: true, depthTest: false, size: 6 });
    this.normals = growable('lines', 0xffe14d, { depthTest: false });
    this.normalLength = 0.1;   // m; main.js sizes it to the scene
    this.counts = { cast: { rays: 0, hits: 0 }, sensors: { rays: 0, hits: 0 } };
    this.changed = false;
    scene.add(this.lines, this.hits, this.normals);
  }

  apply(frame) { this.frames[frame.kind] = frame; this.changed = true; }

  setVisible(v) { this.lines.visible = this.hits.visible = this.normals.visible = v; }

  // rewrites the overlays (tens to thousands of rays: cheap beside the bodies)
  update(bodies) {
    if (!this.frames[0] && !this.frames[1]) return;
    const line = [], lineColor = [], hit = [], hitColor = [], normal = [], L = this.normalLength;
    const o = new THREE.Vector3(), e = new THREE.Vector3();
    for (const kind of [0, 1]) {
      const f = this.frames[kind];
      const count = { rays: 0, hits: 0 };
      for (let i = 0; f && i < f.n; i++) {
        const r = f.rows.subarray(i * RAY_WIDTH, (i + 1) * RAY_WIDTH);
        o.set(r[1], r[2], r[3]);
        if (kind === 1) {
          const pose = bodies.pose(r[0]);
          if (!pose) continue;
          o.applyQuaternion(pose.q).add(pose.p);
        }
        e.set(r[4], r[5], r[6]);
        const c = r[7] ? HIT[kind] : MISS;
        line.push(o.x, o.y, o.z, e.x, e.y, e.z);
        lineColor.push(c.r, c.g, c.b, c.r, c.g, c.b);
        count.rays += 1;
        if (r[7]) { hit.push(e.x, e.y, e.z); hitColor.push(c.r, c.g, c.b); count.hits += 1; }
        if (r[7] && (r[8] || r[9] || r[10])) {
          normal.push(e.x, e.y, e.z, e.x + L * r[8], e.y + L * r[9], e.z + L * r[10]);
        }
      }
      this.counts[kind ? 'sensors' : 'cast'] = count;
    }
    for (const [obj, pos, col] of [[this.lines, line, lineColor], [this.hits, hit, hitColor]]) {
      fill(obj, pos.length / 3, (a) => a.set(pos), 'position');
      fill(obj, col.length / 3, (a) => a.set(col), 'color');
    }
    fill(this.normals, normal.length / 3, (a) => a.set(normal));
    this.changed = false;
  }
}
