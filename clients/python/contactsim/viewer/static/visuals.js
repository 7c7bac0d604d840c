// One visual element of a model's link as a three.js object in the link
// frame: boxes, spheres, cylinders and capsules built here, meshes (OBJ,
// STL, Collada) loaded from the bridge's /meshes/ (meshes.py) once per file
// and cloned for each use. Sizes and poses are the file's (docs/models.md).
import * as THREE from 'three';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';
import { STLLoader } from 'three/addons/loaders/STLLoader.js';
import { ColladaLoader } from 'three/addons/loaders/ColladaLoader.js';

const files = new Map();   // url -> Promise of a template Object3D

function material(rgba) {
  return new THREE.MeshLambertMaterial({ color: new THREE.Color(rgba[0], rgba[1], rgba[2]), opacity: rgba[3],
                                         transparent: rgba[3] < 1 });
}

// three's cylinder and capsule run along y; a URDF's along the element's z
function alongZ(geometry) { geometry.rotateX(Math.PI / 2); return geometry; }

function primitive(v) {
  switch (v.kind) {
    case 'box': return new THREE.BoxGeometry(...v.size);
    case 'sphere': return new THREE.SphereGeometry(v.radius, 24, 16);
    case 'cylinder': return alongZ(new THREE.CylinderGeometry(v.radius, v.radius, v.length, 24));
    case 'capsule': return alongZ(new THREE.CapsuleGeometry(v.radius, v.length, 6, 16));
    default: return null;
  }
}

// the file's object, with materials of its own (Collada) or the element's colour (OBJ, STL)
function load(url) {
  if (!files.has(url)) {
    const ext = url.split('.').pop().toLowerCase();
    let p;
    if (ext === 'stl') {
      p = new STLLoader().loadAsync(url).then((g) => new THREE.Mesh(g));
    } else if (ext === 'obj') {
      p = new OBJLoader().loadAsync(url);
    } else if (ext === 'dae') {
      // ColladaLoader turns a Z_UP file to three's y up: our world is z up,
      // so the file's axes are kept (its unit scale is kept)
      p = new ColladaLoader().loadAsync(url).then((c) => { c.scene.rotation.set(0, 0, 0); return c.scene; });
    } else {
      p = Promise.reject(new Error(`no loader for ${url}`));
    }
    files.set(url, p);
  }
  return files.get(url);
}

// {object, loading}: the element posed in its link frame; loading (a mesh
// only) resolves true once the file's object is in it, false if it failed
export function visualObject(v) {
  const object = new THREE.Group();
  const q = v.orientation;
  object.position.set(...v.position);
  object.quaternion.set(q[1], q[2], q[3], q[0]);   // ours (w, x, y, z)
  if (v.kind !== 'mesh') {
    const g = primitive(v);
    if (g) object.add(new THREE.Mesh(g, material(v.rgba)));
    return { object, loading: null };
  }
  object.scale.set(...v.scale);
  const own = v.url.endsWith('.dae');
  const loading = load(v.url).then((template) => {
    const copy = template.clone(true);
    if (!own) copy.traverse((m) => { if (m.isMesh) m.material = material(v.rgba); });
    object.add(copy);
    return true;
  }, (e) => { console.warn(`contactsim-viewer: ${v.url}: ${e}`); return false; });
  return { object, loading };
}

// whether the page can draw the element (a mesh needs a file the bridge serves)
export function drawable(v) { return v.kind === 'mesh' ? Boolean(v.url) : primitive(v) !== null; }
