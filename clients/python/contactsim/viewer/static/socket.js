// The WebSocket to the bridge: JSON messages and binary frames (docs/viewer.md).
// Binary frames are little-endian Float64Arrays whose first value names them.
export const POSES = 1, CONTACTS = 2, RAYS = 3;
export const POSE_WIDTH = 8, CONTACT_WIDTH = 6, RAY_WIDTH = 11;

export function connect(handlers) {
  const ws = new WebSocket(`ws://${location.host}/ws`);
  ws.binaryType = 'arraybuffer';
  let nextId = 1;
  ws.onmessage = (ev) => {
    if (typeof ev.data === 'string') {
      const msg = JSON.parse(ev.data);
      (handlers[msg.type] || (() => {}))(msg);
      return;
    }
    const a = new Float64Array(ev.data);
    if (a[0] === POSES) handlers.poses(decodePoses(a));
    else if (a[0] === CONTACTS) handlers.contacts(decodeContacts(a));
    else if (a[0] === RAYS) handlers.rays(decodeRays(a));
  };
  ws.onclose = () => (handlers.closed || (() => {}))();
  return {
    send(obj) { if (ws.readyState === WebSocket.OPEN) ws.send(JSON.stringify(obj)); },
    // a command with an id, answered by a {type: "reply", id} message
    command(cmd, args = {}) { const id = nextId++; this.send({ cmd, id, ...args }); return id; },
  };
}

function decodePoses(a) {
  return { step: a[1], time: a[2], kinetic: a[3], potential: a[4], n: a[5], rows: a.subarray(6),
           received: performance.timeOrigin + performance.now() };   // epoch ms, for the latency benchmark
}

function decodeContacts(a) {
  return { step: a[1], n: a[2], rows: a.subarray(3) };
}

// kind 0: a ray cast (origins in the world), 1: range sensors (origins in their bodies' frames)
function decodeRays(a) {
  return { step: a[1], kind: a[2], n: a[3], rows: a.subarray(4) };
}
