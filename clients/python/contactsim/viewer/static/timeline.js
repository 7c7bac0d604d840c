// Replay: a slider over the log's STATEs and a player at any speed. The page
// asks the bridge for STATE i ("seek") and asks for the next one only once
// it has drawn the last, so playing never queues frames.
const $ = (id) => document.getElementById(id);

export class Timeline {
  constructor(socket, hello, panel) {
    this.socket = socket; this.panel = panel;
    this.steps = hello.steps; this.times = hello.times;
    this.kinetic = hello.kinetic; this.potential = hello.potential;
    this.index = 0; this.inFlight = false; this.wanted = null; this.playing = false;
    const slider = $('timeline');
    slider.max = Math.max(0, this.steps.length - 1);
    slider.addEventListener('input', () => this.seek(Number(slider.value)));
    $('btn-play').addEventListener('click', () => this.toggle());
    // a new speed counts from now, not from when play was pressed
    $('speed').addEventListener('change', () => { this.clock = { wall: performance.now(), sim: this.times[this.index] }; });
    $('replay-controls').hidden = false;
    $('live-controls').hidden = true;
    this.seek(0);
  }

  // index of the last STATE at or before simulated time t
  indexAt(t) {
    let lo = 0, hi = this.times.length - 1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (this.times[mid] <= t) lo = mid; else hi = mid - 1; }
    return lo;
  }

  seek(i) {
    i = Math.max(0, Math.min(i, this.steps.length - 1));
    if (this.inFlight) { this.wanted = i; return; }
    this.inFlight = true; this.index = i;
    $('timeline').value = i;
    $('timeline-label').textContent = `step ${this.steps[i]} (${i + 1}/${this.steps.length})`;
    this.panel.plot(this.steps.slice(Math.max(0, i - this.panel.maxSamples + 1), i + 1)
      .map((_, k, arr) => { const j = i - arr.length + 1 + k; return [this.kinetic[j], this.potential[j]]; }));
    this.socket.send({ cmd: 'seek', index: i });
  }

  // called when the frame of the last seek is drawn
  drawn() {
    this.inFlight = false;
    if (this.wanted !== null) { const w = this.wanted; this.wanted = null; this.seek(w); }
  }

  toggle() {
    this.playing = !this.playing;
    $('btn-play').textContent = this.playing ? 'stop' : 'play';
    if (this.playing && this.index >= this.steps.length - 1) this.seek(0);
    this.clock = { wall: performance.now(), sim: this.times[this.index] };
  }

  // advances the player by the wall time elapsed times the chosen speed
  tick(now) {
    if (!this.playing || this.inFlight) return;
    const t = this.clock.sim + ((now - this.clock.wall) / 1000) * Number($('speed').value);
    const i = this.indexAt(t);
    if (i >= this.steps.length - 1) this.toggle();
    if (i !== this.index) this.seek(i);
  }
}
