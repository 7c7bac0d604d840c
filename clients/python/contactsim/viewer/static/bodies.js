// Every body at its pose: one InstancedMesh per shape group (shapes.js),
// rebuilt when the catalog or the set of body ids changes, updated in place
// from each POSES frame. Compound bodies and the bodies of robot models are
// one object each (their collision shapes at real size), since a model's
// collision shapes are shown, overlaid or hidden beside its visuals
// (models.js) per body; so are triangle meshes and heightfields, each of
// its own vertices (surfaces.js).
import * as THREE from 'three';
import { POSE_WIDTH } from './socket.js';
import { collisionObject, planeObject, shapeGroup } from './shapes.js';
import { isSurface, surfaceMaterial } from './surfaces.js';

const COLORS = { sphere: 0xd9a441, box: 0x5b8fd9, capsule: 0x6fbf73, convex: 0xb07cd9, marker: 0xaaaaaa,
                 compound: 0xd97b5b };
const OVERLAY = new THREE.MeshBasicMaterial({ color: 0xffa040, wireframe: true, transparent: true, opacity: 0.6 });
const STATIC_COLOR = 0x7a7f88;

// neighbours of one kind differ a little in lightness, so that a stack reads as bodies
function shade(color, id) {
  const c = new THREE.Color(color);
  return c.offsetHSL(0, 0, (((id * 2654435761) >>> 0) % 17 - 8) / 100);
}

export class Bodies {
  constructor(scene) {
    this.root = new THREE.Group();
    scene.add(this.root);
    this.catalog = new Map();   // id -> catalog body
    this.slots = new Map();     // id -> {mesh, index, scale} (planes: {plane: true}; objects: {object})
    this.modelBodies = new Set();  // bodies drawn as objects: they carry a model's links
    this.visualBodies = new Set(); // those of them whose links have visuals
    this.collision = 'visual';     // 'visual': hidden where visuals are, 'both': overlaid, 'collision': solid
    this.meshes = [];
    this.rowOf = new Map();     // id -> row of the latest POSES frame
    this.frame = null;
    this._m = new THREE.Matrix4(); this._p = new THREE.Vector3(); this._q = new THREE.Quaternion();
    this._s = new THREE.Vector3();
  }

  // bodies: the catalog's; modelBodies and visualBodies: Sets of ids (models.js)
  setCatalog(bodies, modelBodies = new Set(), visualBodies = new Set()) {
    this.catalog = new Map(bodies.map((b) => [b.id, b]));
    this.modelBodies = modelBodies;
    this.visualBodies = visualBodies;
    this.slots.clear();   // rebuilt at the next frame
  }

  // how the collision shapes of bodies with visuals are drawn
  setCollisionMode(mode) {
    this.collision = mode;
    for (const [id, slot] of this.slots) if (slot.object) this._style(id, slot.object);
  }

  _style(id, object) {
    const covered = this.visualBodies.has(id);
    object.visible = !covered || this.collision !== 'visual';
    const overlay = covered && this.collision === 'both';
    object.traverse((m) => { if (m.isMesh) m.material = overlay ? OVERLAY : object.userData.solid; });
  }

  _object(id, body) {
    const color = body.motion !== 'dynamic' ? STATIC_COLOR : shade(COLORS.compound, id);
    const solid = isSurface(body.shape) ? surfaceMaterial(body.shape, color) : new THREE.MeshLambertMaterial({ color });
    const object = collisionObject(body.shape, solid);
    object.userData = { id, solid };
    this._style(id, object);
    this.root.add(object); this.meshes.push(object);
    this.slots.set(id, { object });
  }

  // lays out the ids of a frame into instanced groups (only when they change)
  _layout(ids) {
    for (const m of this.meshes) {
      this.root.remove(m);
      m.traverse((o) => { if (o.geometry) o.geometry.dispose(); });
    }
    this.meshes = [];
    this.slots.clear();
    const groups = new Map();
    for (const id of ids) {
      const body = this.catalog.get(id);
      if (body && body.shape.kind === 'plane') {
        const obj = planeObject(body.shape, 60);
        this.root.add(obj); this.meshes.push(obj);
        this.slots.set(id, { plane: true });
        continue;
      }
      if (body && (body.shape.kind === 'compound' || isSurface(body.shape) || this.modelBodies.has(id))) {
        this._object(id, body);
        continue;
      }
      const g = shapeGroup(body && body.shape);
      const still = body && body.motion !== 'dynamic';
      const key = g.key + (still ? ':static' : '');
      if (!groups.has(key)) groups.set(key, { g, still, ids: [] });
      groups.get(key).ids.push(id);
    }
    for (const { g, still, ids: members } of groups.values()) {
      const color = still ? STATIC_COLOR : COLORS[g.key.split(':')[0]];
      // white material: the per-instance colours (shade) carry the kind's colour
      const mesh = new THREE.InstancedMesh(g.make(members.length), new THREE.MeshLambertMaterial(),
                                           members.length);
      mesh.frustumCulled = false;   // instances move; the geometry's bounds say nothing of them
      mesh.userData.ids = members;
      members.forEach((id, index) => {
        this.slots.set(id, { mesh, index, scale: g.scale });
        mesh.setColorAt(index, shade(color, id));
      });
      this.root.add(mesh); this.meshes.push(mesh);
    }
  }

  apply(frame) {
    const r = frame.rows, n = frame.n;
    let relayout = n !== this.slots.size;
    for (let i = 0; i < n && !relayout; i++) relayout = !this.slots.has(r[i * POSE_WIDTH]);
    if (relayout) this._layout(Array.from({ length: n }, (_, i) => r[i * POSE_WIDTH]));
    this.rowOf.clear();
    for (let i = 0; i < n; i++) {
      const o = i * POSE_WIDTH, id = r[o];
      this.rowOf.set(id, i);
      const slot = this.slots.get(id);
      if (slot.plane) continue;
      this._p.set(r[o + 1], r[o + 2], r[o + 3]);
      this._q.set(r[o + 5], r[o + 6], r[o + 7], r[o + 4]);   // ours (w, x, y, z); three's (x, y, z, w)
      if (slot.object) { slot.object.position.copy(this._p); slot.object.quaternion.copy(this._q); continue; }
      this._s.set(...slot.scale);
      slot.mesh.setMatrixAt(slot.index, this._m.compose(this._p, this._q, this._s));
    }
    for (const m of this.meshes) {
      if (m.isInstancedMesh) { m.instanceMatrix.needsUpdate = true; m.boundingSphere = null; }
    }
    this.frame = frame;
    return relayout;
  }

  // position (Vector3) and orientation (Quaternion) of a body in the latest frame, or null
  pose(id) {
    const i = this.rowOf.get(id);
    if (i === undefined) return null;
    const r = this.frame.rows, o = i * POSE_WIDTH;
    return { p: new THREE.Vector3(r[o + 1], r[o + 2], r[o + 3]),
             q: new THREE.Quaternion(r[o + 5], r[o + 6], r[o + 7], r[o + 4]) };
  }

  // id -> [x, y, z] read back from the instance matrices of the scene graph (tests use this)
  positions() {
    const out = {};
    for (const [id, slot] of this.slots) {
      if (slot.plane) continue;
      if (slot.object) { out[id] = slot.object.position.toArray(); continue; }
      slot.mesh.getMatrixAt(slot.index, this._m);
      this._p.setFromMatrixPosition(this._m);
      out[id] = [this._p.x, this._p.y, this._p.z];
    }
    return out;
  }

  // how many collision objects (compounds, model bodies) are drawn solid and as an overlay
  shownObjects() {
    const out = { solid: 0, overlay: 0 };
    for (const slot of this.slots.values()) {
      if (!slot.object || !slot.object.visible) continue;
      let overlay = false;
      slot.object.traverse((m) => { if (m.isMesh && m.material === OVERLAY) overlay = true; });
      out[overlay ? 'overlay' : 'solid'] += 1;
    }
    return out;
  }

  // {id, distance} of the nearest body under a ray, or null
  pick(raycaster) {
    const hits = raycaster.intersectObjects(this.meshes.filter((m) => m.isInstancedMesh || m.userData.solid), true);
    for (const h of hits) {
      if (h.instanceId !== undefined) return { id: h.object.userData.ids[h.instanceId], distance: h.distance };
      const object = h.object.parent;
      if (object && object.visible && object.userData.solid) return { id: object.userData.id, distance: h.distance };
    }
    return null;
  }

  // centre and radius of the dynamic bodies' positions (for framing the camera)
  bounds() {
    const box = new THREE.Box3();
    for (const [id, slot] of this.slots) {
      const pose = slot.plane ? null : this.pose(id);
      if (pose) box.expandByPoint(pose.p);
    }
    if (box.isEmpty()) return { centre: new THREE.Vector3(), radius: 2 };
    const s = box.getBoundingSphere(new THREE.Sphere());
    return { centre: s.center, radius: Math.max(s.radius, 0.5) };
  }
}
