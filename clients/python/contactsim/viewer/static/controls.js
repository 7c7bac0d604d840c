// The live controls: every button becomes one command to the bridge, which
// runs it through the Python client (docs/viewer.md, "commands").
const $ = (id) => document.getElementById(id);

export function wireLiveControls(socket) {
  const on = (id, fn) => $(id).addEventListener('click', fn);
  on('btn-pause', () => socket.command('pause'));
  on('btn-resume', () => socket.command('resume'));
  on('btn-step', () => socket.command('step', { n: Number($('step-n').value) || 1 }));
  on('btn-method', () => socket.command('method', { name: $('method-select').value, params: $('method-params').value }));
  on('btn-reset', () => socket.command('reset'));
  on('btn-load', () => socket.command('load', { path: $('scene-select').value }));
  on('btn-snapshot', () => socket.command('snapshot', { name: 'viewer' }));
  on('btn-restore', () => socket.command('restore', { name: 'viewer' }));
  on('btn-rewind', () => socket.command('rewind', { step: Number($('rewind-step').value) || 0 }));
}

// fills a select with names, keeping the current choice when it is still there
export function setOptions(id, names, labels = (x) => x) {
  const sel = $(id), keep = sel.value;
  sel.replaceChildren(...names.map((n) => { const o = document.createElement('option'); o.value = n; o.textContent = labels(n); return o; }));
  if (names.includes(keep)) sel.value = keep;
}

// the active method joins the documented ones, and is selected until the user picks another
export function showMethod(methods, active) {
  if (active && !methods.includes(active)) methods.push(active);
  const sel = $('method-select');
  const untouched = !sel.dataset.touched;
  setOptions('method-select', methods);
  if (untouched && active) sel.value = active;
  sel.onchange = () => { sel.dataset.touched = '1'; };
}
