// Wires the page: socket -> bodies, overlays, panel; controls -> commands.
// window.contactsimViewer exposes the scene state to tests and scripts.
import { Bodies } from './bodies.js';
import { showMethod, setOptions, wireLiveControls } from './controls.js';
import { JointPanel } from './joint_panel.js';
import { Models } from './models.js';
import { Contacts, Joints } from './overlays.js';
import { Panel } from './panel.js';
import { Rays } from './rays.js';
import { connect } from './socket.js';
import { decodeSurfaces } from './surface_data.js';
import { Timeline } from './timeline.js';
import { World } from './world.js';

const $ = (id) => document.getElementById(id);
const world = new World($('view'));
const bodies = new Bodies(world.scene);
const contacts = new Contacts(world.scene);
const joints = new Joints(world.scene);
const models = new Models(world.scene, () => { world.dirty = true; });
const rays = new Rays(world.scene);
const jointPanel = new JointPanel($('joints'), (joint, position) => socket.command('joint_target', { joint, position }));
const panel = new Panel();
const state = { hello: null, status: null, pending: null, drawn: 0, step: null, selected: null,
                framed: false, renders: 0, updateMs: [], frameLog: [], timeline: null, replies: [],
                surfaceErrors: [] };

const socket = connect({
  hello(msg) {
    state.hello = msg;
    jointPanel.live = msg.mode === 'live';
    $('mode').textContent = msg.mode === 'replay' ? `replay: ${msg.log}` : `live: ${msg.prefix}`;
    if (msg.mode === 'replay') { state.timeline = new Timeline(socket, msg, panel); return; }
    showMethod(msg.methods.slice(), null);
    setOptions('scene-select', msg.scenes, (p) => p.split('/').pop());
  },
  catalog(msg) {
    // ids restart with a new scene: a selection survives only if its body is the same one
    const before = state.selected !== null ? bodies.catalog.get(state.selected) : null;
    state.surfaceErrors = decodeSurfaces(msg.bodies);   // a refused surface is drawn as a marker
    if (state.surfaceErrors.length) panel.message(state.surfaceErrors.join('\n'), false);
    const { modelBodies, visualBodies } = models.setCatalog(msg.models);
    bodies.setCatalog(msg.bodies, modelBodies, visualBodies); joints.setCatalog(msg.joints); state.framed = false;
    jointPanel.setCatalog(msg.models, msg.joints);
    const after = state.selected !== null ? bodies.catalog.get(state.selected) : null;
    if (!before || !after || before.name !== after.name) state.selected = null;
  },
  status(msg) {
    state.status = msg; panel.status(msg);
    if (state.hello.mode === 'live') showMethod(state.hello.methods.slice(), msg.method);
  },
  poses(frame) { state.pending = frame; },   // drawn at the next animation frame
  contacts(frame) { contacts.apply(frame); panel.contacts(frame.n); },
  rays(frame) { rays.apply(frame); },
  reply(msg) { state.replies.push(msg); jointPanel.reply(msg); panel.message(`${msg.cmd}: ${msg.message}`, msg.ok); },
  error(msg) { panel.message(msg.message, false); },
  body(msg) { $('selection').textContent = describe(msg); },
  closed() { panel.message('disconnected from the bridge', false); },
});
if (!state.timeline) wireLiveControls(socket);

function describe(b) {
  const v = (a) => (a ? a.map((x) => x.toFixed(3)).join(', ') : '-');
  return `id ${b.id} ${b.name ? `"${b.name}"` : ''}\n${b.shape ? b.shape.kind : 'shape unknown'}, ${b.motion || ''}` +
    `${b.shape && b.shape.error ? `\n${b.shape.error}` : ''}` +
    `\nmass ${b.mass !== undefined ? b.mass.toFixed(4) + ' kg' : '-'}\nposition ${v(b.position)}` +
    `\nvelocity ${v(b.linear_velocity)} m/s\nangular ${v(b.angular_velocity)} rad/s`;
}

// draws the newest frame, then tells the bridge it may send the next
function draw(frame) {
  if (state.step !== null && frame.step < state.step) panel.energy = [];   // a reset, load or rewind
  bodies.apply(frame);
  panel.poses(frame);
  if (!state.timeline && Number.isFinite(frame.kinetic)) panel.pushEnergy(frame.kinetic, frame.potential);
  if (!state.framed) {
    const { centre, radius } = bodies.bounds();
    world.fit(centre, radius);
    contacts.normalLength = rays.normalLength = Math.max(0.05, radius * 0.04);
    state.framed = true;
  }
}

function animate(now) {
  requestAnimationFrame(animate);
  const frame = state.pending;
  state.pending = null;
  if (frame) {
    const t0 = performance.now();
    draw(frame);
    state.updateMs.push(performance.now() - t0);
    if (state.updateMs.length > 1000) state.updateMs.shift();
    world.dirty = true;
  }
  if (state.timeline) state.timeline.tick(now);
  if (frame || contacts.changed) { joints.update(bodies); contacts.changed = false; world.dirty = true; }
  if (frame) { models.update(bodies); jointPanel.update(bodies); }
  if (frame || rays.changed) { rays.update(bodies); world.dirty = true; }
  const sel = state.selected !== null && $('follow').checked ? bodies.pose(state.selected) : null;
  if (sel && frame) world.follow(sel.p);
  if (world.render()) state.renders += 1;
  if (frame) {
    state.drawn += 1; state.step = frame.step;
    state.frameLog.push([frame.step, frame.received, performance.timeOrigin + performance.now()]);
    if (state.frameLog.length > 100000) state.frameLog.splice(0, 50000);
    if (state.timeline) state.timeline.drawn(); else socket.send({ cmd: 'ack' });
  }
}
requestAnimationFrame(animate);

world.renderer.domElement.addEventListener('click', (ev) => {
  const ray = world.ray(ev);
  const hits = [models.pick(ray), bodies.pick(ray)].filter((h) => h !== null);
  if (!hits.length) return;
  const id = hits.reduce((a, b) => (b.distance < a.distance ? b : a)).id;   // the nearer of a visual and a shape
  state.selected = id;
  if (state.hello && state.hello.mode === 'live') socket.send({ cmd: 'body', id });
  else $('selection').textContent = describe({ id, ...(bodies.catalog.get(id) || {}) });
});
$('show-contacts').addEventListener('change', (ev) => { contacts.setVisible(ev.target.checked); world.dirty = true; });
$('btn-fit').addEventListener('click', () => { const b = bodies.bounds(); world.fit(b.centre, b.radius); });
$('follow').addEventListener('change', () => { world.dirty = true; });
$('show-rays').addEventListener('change', (ev) => { rays.setVisible(ev.target.checked); world.dirty = true; });
$('collision-mode').addEventListener('change', (ev) => {
  bodies.setCollisionMode(ev.target.value);
  models.setVisible(ev.target.value !== 'collision');
  world.dirty = true;
});

window.contactsimViewer = {
  bodies: () => bodies.positions(),          // id -> [x, y, z] from the instance matrices
  framesDrawn: () => state.drawn,           // POSES frames drawn
  renders: () => state.renders,              // renders (the page draws only when something changed)
  step: () => state.step,
  mode: () => (state.hello ? state.hello.mode : null),
  status: () => state.status,
  contactCount: () => contacts.count,
  updateMs: () => state.updateMs,            // ms to apply each drawn frame to the scene graph (not to render it)
  frameLog: () => state.frameLog,            // [step, epoch ms received, epoch ms drawn]
  replies: () => state.replies,
  seek: (i) => state.timeline && state.timeline.seek(i),
  timelineSteps: () => (state.timeline ? state.timeline.steps : []),
  select: (id) => { state.selected = id; },
  models: () => models.counts(),             // bodies with visuals, three.js meshes drawn, mesh files loaded / failed
  collisionShown: () => bodies.shownObjects(),  // {solid, overlay}: collision objects of model and compound bodies drawn
  surfaceErrors: () => state.surfaceErrors,  // "body <id> (<name>): <why>" of each surface drawn as a marker
  rays: () => rays.counts,                   // {cast, sensors}: {rays, hits} drawn
  jointValues: () => jointPanel.values,      // "model/joint" -> rad or m at the drawn poses
  jointTargets: () => jointPanel.targets,    // "model/joint" -> the last slider target the server accepted
  internals: { world, bodies, contacts, joints, models, rays },
};
