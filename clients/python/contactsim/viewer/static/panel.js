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
    $('ro-bodies').textContent = s.num_bodies;
    $('ro-paused').textContent = `${s.paused ? 'paused' : 'running'}, ${s.mode}`;
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

  // kinetic (orange), potential (blue) and their sum (white), scaled to the samples shown
  plot(samples) {
    const c = this.canvas, g = c.getContext('2d');
    g.clearRect(0, 0, c.width, c.height);
    if (samples.length < 2) return;
    let lo = Infinity, hi = -Infinity;
    for (const [k, p] of samples) { lo = Math.min(lo, k, p, k + p); hi = Math.max(hi, k, p, k + p); }
    if (hi - lo < 1e-9) { hi += 1; lo -= 1; }
    const x = (i) => (i / (this.maxSamples - 1)) * c.width;
    const y = (v) => c.height - 4 - ((v - lo) / (hi - lo)) * (c.height - 8);
    for (const [color, pick] of [['#f0a040', (s) => s[0]], ['#4da3ff', (s) => s[1]], ['#eeeeee', (s) => s[0] + s[1]]]) {
      g.strokeStyle = color;
      g.beginPath();
      samples.forEach((s, i) => (i ? g.lineTo(x(i), y(pick(s))) : g.moveTo(x(i), y(pick(s)))));
      g.stroke();
    }
  }
}
