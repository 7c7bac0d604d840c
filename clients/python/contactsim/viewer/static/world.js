// The three.js scene, camera (z up, as the simulation), lights, orbit
// controls, and the camera that follows a selected body.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// A software renderer (SwiftShader in headless chromium, llvmpipe) pays for
// multisampling on every pixel: 2.5 times the frame time on a 1,000-body
// scene (BENCHMARKS.md). Off there, on elsewhere; ?aa=1 or ?aa=0 decides.
function wantAntialias() {
  const asked = new URLSearchParams(location.search).get('aa');
  if (asked !== null) return asked !== '0';
  const gl = document.createElement('canvas').getContext('webgl2');
  const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
  const lose = gl && gl.getExtension('WEBGL_lose_context');
  if (lose) lose.loseContext();
  return !/swiftshader|llvmpipe|software/i.test(name);
}

export class World {
  constructor(container) {
    this.container = container;
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x1b1d22);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.01, 2000);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(6, -8, 5);
    this.renderer = new THREE.WebGLRenderer({ antialias: wantAntialias() });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
    container.appendChild(this.renderer.domElement);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    // draw only when something changed: an idle page costs no CPU (a software
    // renderer on a shared machine spends whole cores on redrawing the same picture)
    this.dirty = true;
    this.controls.addEventListener('change', () => { this.dirty = true; });
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(5, -3, 10);
    this.scene.add(sun);
    this.raycaster = new THREE.Raycaster();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = this.container.clientWidth || 1, h = this.container.clientHeight || 1;
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  // looks at a sphere (centre, radius) from the current direction
  fit(centre, radius) {
    const dir = this.camera.position.clone().sub(this.controls.target).normalize();
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).addScaledVector(dir, radius * 2.6);
    this.camera.near = radius / 100;
    this.camera.far = radius * 200;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  // moves camera and target with a followed body, keeping the view's offset
  follow(p) {
    const offset = this.camera.position.clone().sub(this.controls.target);
    this.controls.target.copy(p);
    this.camera.position.copy(p).add(offset);
    this.dirty = true;
  }

  // the ray under a mouse event, in normalised device coordinates
  ray(event) {
    const r = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1,
                                  -((event.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.camera);
    return this.raycaster;
  }

  // renders when something changed since the last render; true when it did
  render() {
    if (!this.dirty) return false;
    this.dirty = false;
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
    return true;
  }
}
