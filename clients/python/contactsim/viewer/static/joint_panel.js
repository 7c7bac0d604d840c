// The models' joint coordinates in the panel: each hinge's angle and each
// slider's slide, computed from the drawn poses exactly as the server
// measures them (service/physics/joint.cpp, HingeAngle and PrismaticSlide):
// the hinge angle is that of the twist q_A^-1 q_B rest^-1 about the axis
// fixed in A, the slide a . (p_B - p_A) between the two anchors. Beside each,
// a slider sets the joint's actuator target (ACTUATOR_CMD SET through the bridge).
import * as THREE from 'three';

const WORLD = { p: new THREE.Vector3(), q: new THREE.Quaternion() };

// the coordinate of a catalog joint (hinge: rad, prismatic: m) from the two bodies' poses, or null
export function jointValue(j, bodies) {
  const a = bodies.pose(j.body_a);
  const b = j.body_b ? bodies.pose(j.body_b) : WORLD;
  if (!a || !b) return null;
  const axis = new THREE.Vector3(...j.axis_a);
  if (j.kind === 'hinge') {
    const rest = new THREE.Quaternion(j.rest[1], j.rest[2], j.rest[3], j.rest[0]);
    const t = a.q.clone().invert().multiply(b.q).multiply(rest.invert());
    const s = t.w < 0 ? -1 : 1;   // the same rotation, its angle in [-pi, pi]
    return 2 * Math.atan2(s * (t.x * axis.x + t.y * axis.y + t.z * axis.z), s * t.w);
  }
  if (j.kind === 'prismatic') {
    const pa = new THREE.Vector3(...j.anchor_a).applyQuaternion(a.q).add(a.p);
    const pb = j.body_b ? new THREE.Vector3(...j.anchor_b).applyQuaternion(b.q).add(b.p)
      : new THREE.Vector3(...j.anchor_b);
    return axis.applyQuaternion(a.q).dot(pb.sub(pa));
  }
  return null;
}

// A slider's range: the joint's limits, else a turn (hinge, rad) or a metre
// either way (slider, m).
function targetRange(j) {
  if (j.limited) return [j.lower, j.upper];
  return j.kind === 'hinge' ? [-Math.PI, Math.PI] : [-1, 1];
}

export class JointPanel {
  // send(jointId, position) sends a target and returns the command's id;
  // live: whether the page steers a server (a replay takes no commands)
  constructor(table, send) {
    this.table = table;
    this.send = send;
    this.live = false;
    this.rows = [];    // {key, joint, cell, slider, sent, pending, inflight}
    this.values = {};  // "model/joint" -> rad or m
    this.targets = {}; // "model/joint" -> the last target the server accepted
  }

  // models: the catalog's; joints: the catalog's world joints
  setCatalog(models, joints) {
    const byId = new Map((joints || []).map((j) => [j.id, j]));
    this.rows = [];
    this.values = {};
    this.targets = {};
    const trs = [];
    for (const model of models || []) {
      for (const mj of model.joints) {
        const joint = byId.get(mj.joint);
        if (!joint || (joint.kind !== 'hinge' && joint.kind !== 'prismatic')) continue;
        const tr = document.createElement('tr');
        const name = document.createElement('th'), cell = document.createElement('td');
        const row = { key: `${model.name}/${mj.name}`, joint, cell, sent: null, pending: null, inflight: null };
        row.slider = this._slider(row);
        const slot = document.createElement('td');
        slot.append(row.slider);
        name.textContent = row.key;
        tr.append(name, cell, slot);
        trs.push(tr);
        this.rows.push(row);
      }
    }
    this.table.replaceChildren(...trs);
    this.table.hidden = trs.length === 0;
  }

  // A joint's target slider: live when the joint's actuator has a position
  // gain (docs/actuators.md: the target acts when kp > 0) and the page steers
  // a live server; dragging sends the target, one command in flight a joint.
  _slider(row) {
    const s = document.createElement('input');
    const [lo, hi] = targetRange(row.joint);
    const a = row.joint.actuator;
    Object.assign(s, { type: 'range', min: lo, max: hi, step: (hi - lo) / 1000 });
    s.value = a ? a.target_position : 0;
    s.dataset.joint = row.joint.id;
    s.disabled = !this.live || !a || !(a.kp > 0);
    s.title = !this.live ? 'a replay takes no commands'
      : s.disabled ? 'no position gain: set kp > 0 (docs/actuators.md)' : 'target position';
    s.addEventListener('input', () => { row.pending = Number(s.value); this._flush(row); });
    return s;
  }

  _flush(row) {
    if (row.inflight !== null || row.pending === null || row.pending === row.sent) return;
    row.sent = row.pending;
    row.inflight = this.send(row.joint.id, row.sent);
  }

  // the reply to a command (main.js hands every reply here): frees the
  // slider's joint for its next target
  reply(msg) {
    const row = this.rows.find((r) => r.inflight === msg.id);
    if (!row) return;
    row.inflight = null;
    if (msg.ok) this.targets[row.key] = row.sent;
    this._flush(row);
  }

  // the values at the drawn poses: degrees for hinges (with the limits when set), metres for sliders
  update(bodies) {
    for (const { key, joint, cell } of this.rows) {
      const v = jointValue(joint, bodies);
      this.values[key] = v;
      if (v === null) { cell.textContent = '-'; continue; }
      const deg = (x) => (x * 180 / Math.PI).toFixed(1);
      const limits = joint.limited ? (joint.kind === 'hinge' ? ` [${deg(joint.lower)}, ${deg(joint.upper)}]`
        : ` [${joint.lower.toFixed(3)}, ${joint.upper.toFixed(3)}]`) : '';
      cell.textContent = (joint.kind === 'hinge' ? `${deg(v)}°` : `${v.toFixed(4)} m`) + limits;
    }
  }
}
