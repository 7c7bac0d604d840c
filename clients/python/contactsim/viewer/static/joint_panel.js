// The models' joint coordinates in the panel: each hinge's angle and each
// slider's slide, computed from the drawn poses exactly as the server
// measures them (service/physics/joint.cpp, HingeAngle and PrismaticSlide):
// the hinge angle is that of the twist q_A^-1 q_B rest^-1 about the axis
// fixed in A, the slide a . (p_B - p_A) between the two anchors.
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

export class JointPanel {
  constructor(table) {
    this.table = table;
    this.rows = [];    // {key, joint, cell}
    this.values = {};  // "model/joint" -> rad or m
  }

  // models: the catalog's; joints: the catalog's world joints
  setCatalog(models, joints) {
    const byId = new Map((joints || []).map((j) => [j.id, j]));
    this.rows = [];
    this.values = {};
    const trs = [];
    for (const model of models || []) {
      for (const mj of model.joints) {
        const joint = byId.get(mj.joint);
        if (!joint || (joint.kind !== 'hinge' && joint.kind !== 'prismatic')) continue;
        const tr = document.createElement('tr');
        const name = document.createElement('th'), cell = document.createElement('td');
        name.textContent = `${model.name}/${mj.name}`;
        tr.append(name, cell);
        trs.push(tr);
        this.rows.push({ key: `${model.name}/${mj.name}`, joint, cell });
      }
    }
    this.table.replaceChildren(...trs);
    this.table.hidden = trs.length === 0;
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
