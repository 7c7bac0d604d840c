// The side panel's read-outs and the small live energy plot.
const $ = (id) => document.getElementById(id);
const fmt = (v, digits = 3) => (Number.isFinite(v) ? v.toFixed(digits) : '-');

export class Panel {
  constructor() {
    this.energy = [];          // [kinetic, potential] per drawn frame, newest last
    this.maxSamples = 300;
    this.canvas = $('energy');
  }

  status(s) {
    $('ro-rtf').textContent = fmt(s.real_time_factor, 2);
    $('ro-method').textContent = s.method;
    $('ro-params').textContent = s.method_params || '(defaults)';
    $('ro-contract').textContent = s.method_contract || '-';   // docs/physics.md, "Method contract"
    $('ro-bodies').textContent = s.num_bodies;
    const run = s.paused === null ? 'recorded' : (s.paused ? 'paused' : 'running');   // null: a replay's STATUS
    $('ro-paused').textContent = `${run}, ${s.mode}`;
    if (s.last_error) this.message(`server: ${s.last_error}`, false);
  }

  poses(f) {
    $('ro-step').textContent = f.step;
    $('ro-time').textContent = `${fmt(f.time)} s`;
    $('ro-ke').textContent = `${fmt(f.kinetic)} J`;
    $('ro-pe').textContent = `${fmt(f.potential)} J`;
    $('ro-bodies').textContent = f.n;
  }

  contacts(n) { $('ro-contacts').textContent = n; }

  message(text, ok) {
    const el = $('message');
    el.textContent = text;
    el.className = ok ? 'ok' : '';
  }

  pushEnergy(kinetic, potential) {
    this.energy.push([kinetic, potential]);
    if (this.energy.length > this.maxSamples) this.energy.shift();
    this.plot(this.energy);
  }

  // kinetic (orange), potential (blue) and their sum (white), each on its own
  // scale: potential energy is often orders of magnitude above kinetic
  plot(samples) {
    const c = this.canvas, g = c.getContext('2d');
    g.clearRect(0, 0, c.width, c.height);
    if (samples.length < 2) return;
    const x = (i) => (i / (this.maxSamples - 1)) * c.width;
    const series = [['#f0a040', (s) => s[0]], ['#4da3ff', (s) => s[1]], ['#eeeeee', (s) => s[0] + s[1]]];
    for (const [color, pick] of series) {
      const values = samples.map(pick);
      let lo = Math.min(...values), hi = Math.max(...values);
      if (hi - lo < 1e-9 * Math.max(1, Math.abs(hi))) { hi += 0.5; lo -= 0.5; }
      const y = (v) => c.height - 4 - ((v - lo) / (hi - lo)) * (c.height - 8);
      g.strokeStyle = color;
      g.beginPath();
      values.forEach((v, i) => (i ? g.lineTo(x(i), y(v)) : g.moveTo(x(i), y(v))));
      g.stroke();
    }
  }
}
