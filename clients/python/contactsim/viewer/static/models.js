// The robot models' visuals: for each body that carries links, one group at
// the body's pose holding each link's visual elements at the link's frame in
// the body (the catalog's models, from the snapshot's model records). A
// body whose links have no visual the page can draw shows its collision
// shapes instead (bodies.js).
import * as THREE from 'three';
import { drawable, visualObject } from './visuals.js';

export class Models {
  constructor(scene, onChange) {
    this.root = new THREE.Group();
    scene.add(this.root);
    this.onChange = onChange;     // a mesh arrived: draw again
    this.groups = new Map();      // body id -> Group
    this.models = [];
    this.meshes = { total: 0, loaded: 0, failed: 0 };
    this.visible = true;
    this._generation = 0;
  }

  // {modelBodies, visualBodies}: ids of the bodies carrying links, and of those with a drawable visual
  setCatalog(models) {
    this._generation += 1;
    const generation = this._generation;
    for (const g of this.groups.values()) this.root.remove(g);
    this.groups.clear();
    this.models = models || [];
    this.meshes = { total: 0, loaded: 0, failed: 0 };
    const modelBodies = new Set(), visualBodies = new Set();
    for (const model of this.models) {
      for (const link of model.links) {
        modelBodies.add(link.body);
        const shown = link.visuals.filter(drawable);
        if (!shown.length) continue;
        visualBodies.add(link.body);
        this._link(link, shown, generation);
      }
    }
    return { modelBodies, visualBodies };
  }

  _link(link, visuals, generation) {
    if (!this.groups.has(link.body)) {
      const g = new THREE.Group();
      g.visible = false;   // until the body's first pose
      g.userData.id = link.body;
      this.groups.set(link.body, g);
      this.root.add(g);
    }
    const frame = new THREE.Group();
    const q = link.orientation;
    frame.position.set(...link.position);
    frame.quaternion.set(q[1], q[2], q[3], q[0]);
    frame.name = link.name;
    for (const v of visuals) {
      const { object, loading } = visualObject(v);
      frame.add(object);
      if (!loading) continue;
      this.meshes.total += 1;
      loading.then((ok) => {
        if (generation !== this._generation) return;   // a newer catalog replaced it
        if (ok) this.meshes.loaded += 1; else this.meshes.failed += 1;
        this.onChange();
      });
    }
    this.groups.get(link.body).add(frame);
  }

  setVisible(v) { this.root.visible = this.visible = v; }

  // every group at its body's pose in the latest frame
  update(bodies) {
    for (const [id, g] of this.groups) {
      const pose = bodies.pose(id);
      g.visible = pose !== null;
      if (pose) { g.position.copy(pose.p); g.quaternion.copy(pose.q); }
    }
  }

  // {id, distance} of the nearest visual's body under a ray, or null
  pick(raycaster) {
    if (!this.visible) return null;
    for (const h of raycaster.intersectObjects([...this.groups.values()].filter((g) => g.visible), true)) {
      for (let o = h.object; o; o = o.parent) if (o.userData.id !== undefined) return { id: o.userData.id, distance: h.distance };
    }
    return null;
  }

  // what the scene graph holds: groups (bodies), three.js meshes in them, of which from files
  counts() {
    let meshes = 0;
    this.root.traverse((o) => { if (o.isMesh) meshes += 1; });
    return { bodies: this.groups.size, meshes, ...this.meshes };
  }
}
