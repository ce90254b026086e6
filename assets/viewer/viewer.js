// The shoal mission viewer: reads the plan data embedded in the page, builds the scene and
// wires the controls (time slider, play, vertical exaggeration), the legend and the metrics.
// `window.shoalViewer` exposes the state to tests.
import { MissionScene, COLORS, DEPTH_STOPS, auvColor } from 'shoal/scene';

const $ = (id) => document.getElementById(id);
const data = JSON.parse($('plan-data').textContent);

// Global steps: window 0 from k = 0, then k = 1..=K of every window (step k = 0 of window w + 1
// is step K of window w).
const timeline = [{ w: 0, k: 0 }];
data.windows.forEach((win, w) => {
  for (let k = 1; k < win.usv.length; k++) timeline.push({ w, k });
});
const last = timeline.length - 1;

function clock(t) {
  const s = Math.round(t);
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  return h > 0 ? `${h} h ${String(m).padStart(2, '0')} min` : `${m} min ${String(r).padStart(2, '0')} s`;
}

function stepLabel(g) {
  const { w, k } = timeline[g];
  const win = data.windows[w];
  const t = win.start_time + k * data.dt;
  return `step ${g} / ${last} · window ${w}, k = ${k} / ${win.usv.length - 1} · t = ${Math.round(t)} s (${clock(t)})`;
}

const el = (tag, attrs = {}, text) => {
  const e = document.createElement(tag);
  Object.entries(attrs).forEach(([k, v]) => e.setAttribute(k, v));
  if (text !== undefined) e.textContent = text;
  return e;
};

function legend() {
  const box = $('legend');
  const item = (color, label, cls = 'swatch') => {
    const row = el('span', { class: 'item' });
    const sw = el('span', { class: cls });
    sw.style.background = color;
    row.append(sw, label);
    box.append(row);
  };
  item(COLORS.usv, 'USV');
  for (let i = 0; i < data.auvs; i++) item(auvColor(data, i), `AUV ${i}`);
  item(COLORS.a2u, 'A2U link', 'bar');
  item(COLORS.a2a, 'A2A link', 'bar');
  if (data.sim) {
    const e = data.sim.estimate;
    $('layers').hidden = false;
    $('estimate-name').textContent = e ? `(${e.policy}, ${e.estimator}, ${e.flown})` : '(none: every estimator failed)';
    const dt = data.sim.times.length > 1 ? data.sim.times[1] - data.sim.times[0] : 0;
    $('sim-note').textContent =
      `simulation seed ${data.sim.seed}: ${data.sim.times.length} epochs every ${+dt.toFixed(3)} s` +
      (e ? `; estimate RMS error ${e.team_rmse_m.toFixed(2)} m. ` : '. ') +
      'The AUV markers follow the executed tracks while they are shown, else the planned paths.';
  }
  const f = data.floor;
  $('depthbar').style.background = `linear-gradient(to right, ${DEPTH_STOPS.join(', ')})`;
  $('depth-lo').textContent = `${f.z_lo.toFixed(0)} m`;
  $('depth-hi').textContent = `${f.z_hi.toFixed(0)} m`;
}

const METRICS = [
  ['input_energy', 'input energy, (m/s²)²', (v) => v.toFixed(3)],
  ['explored_area_km2', 'explored area, km²', (v) => v.toFixed(3)],
  ['mean_height', 'mean height, m', (v) => v.toFixed(1)],
  ['min_height', 'min height, m', (v) => v.toFixed(2)],
  ['connected_fraction', 'connected, %', (v) => (100 * v).toFixed(1)],
  ['chain_fraction', 'chain in range & sight, %', (v) => (100 * v).toFixed(1)],
  ['max_heading_rate', 'max ψ̇, rad/s', (v) => v.toExponential(2)],
  ['step1_time_s', 'Step 1 time, s', (v) => v.toFixed(2)],
  ['step3_time_s', 'Step 3 time, s', (v) => v.toFixed(2)],
];

function metricsTable() {
  const table = $('metrics');
  const head = el('tr');
  head.append(el('th', {}, ''), el('th', {}, 'mission'));
  data.windows.forEach((_, w) => head.append(el('th', { 'data-window': w }, `w${w}`)));
  table.append(head);
  const row = (label, cells) => {
    const tr = el('tr');
    tr.append(el('th', {}, label));
    cells.forEach((c, i) => tr.append(el('td', i > 0 ? { 'data-window': i - 1 } : {}, c)));
    table.append(tr);
  };
  for (const [key, label, fmt] of METRICS) {
    const v = (m) => (Number.isFinite(m[key]) ? fmt(m[key]) : '–');
    row(label, [v(data.metrics), ...data.windows.map((win) => v(win.metrics))]);
  }
  const status = (win) => `${win.status === 'converged' ? 'conv.' : win.status}/${win.iterations}`;
  row('Step 3 status/iterations', ['', ...data.windows.map(status)]);
  row('links out of band', [
    String(data.windows.reduce((n, win) => n + win.out_of_band.length, 0)),
    ...data.windows.map((win) => String(win.out_of_band.length)),
  ]);
  const f = data.floor;
  $('about').textContent =
    `${data.auvs} AUVs · K = ${data.steps} steps of δ = ${data.dt} s · ${data.windows.length} window(s) · ` +
    `seed ${data.seed} · d_s = ${data.sonar_range} m, d_t = ${data.band_tolerance} m · ` +
    `floor: ${f.source}, ${f.grid_nx} × ${f.grid_ny} nodes of ${f.grid_dx} m, shown ` +
    `${f.nx} × ${f.ny} vertices of ${f.dx} m · plan by shoal ${data.shoal_version} from ${data.scenario_source}`;
}

// The links of the current step with their lengths (in the unexaggerated plan).
function linkList(g) {
  const { w, k } = timeline[g];
  const win = data.windows[w];
  const pos = (i) => (i === null ? [win.usv[k][0], win.usv[k][1], 0] : win.auvs[i][k]);
  const out = new Set(win.out_of_band.filter((o) => o[0] === k).map((o) => `${o[1]}-${o[2]}`));
  const list = $('links');
  list.replaceChildren();
  for (const [a, b] of win.links[k] || []) {
    const [p, q] = [pos(a), pos(b)];
    const len = Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
    const name = b === null ? `AUV ${a} – USV` : `AUV ${a} – AUV ${b}`;
    const li = el('li', { class: b === null ? 'a2u' : 'a2a' }, `${name}: ${len.toFixed(1)} m`);
    if (out.has(`${a}-${b}`)) {
      li.classList.add('out');
      li.title = 'outside its band';
    }
    list.append(li);
  }
  if (!list.children.length) list.append(el('li', {}, 'none recorded'));
  $('links-note').textContent = k === 0
    ? 'k = 0 is the window\'s fixed start: its links are reported, not planned.'
    : '';
  $('links-note').hidden = k !== 0;
  document.querySelectorAll('#metrics [data-window]').forEach((c) => {
    c.classList.toggle('current', Number(c.dataset.window) === w);
  });
}

function main() {
  document.title = data.title;
  $('title').textContent = data.title;
  legend();
  metricsTable();
  const host = $('scene');
  const scene = new MissionScene(data, timeline, host);
  const f = data.floor;
  // Vertical exaggeration: the relief a twelfth of the floor's width, the water column at
  // most a third of it.
  const relief = Math.max(f.z_hi - f.z_lo, 1);
  const column = Math.max(-f.z_lo, 1);
  const fit = Math.min(scene.extent / (12 * relief), scene.extent / (3 * column));
  const auto = Math.min(20, Math.max(1, Math.round(2 * fit) / 2));
  const exag = $('exag');
  exag.value = String(auto);
  const slider = $('step');
  slider.max = String(last);

  const show = (g) => {
    g = Math.min(Math.max(g, 0), last);
    slider.value = String(g);
    scene.setStep(g);
    $('step-label').textContent = stepLabel(g);
    linkList(g);
    state.step = g;
  };
  const setExag = (e) => {
    scene.setExaggeration(e);
    $('exag-label').textContent = `${e}×`;
    state.exaggeration = e;
  };
  let timer = null;
  const speed = () => 400 / Number($('speed').value);
  const pause = () => {
    clearInterval(timer);
    timer = null;
    $('play').textContent = '▶ play';
  };
  const play = () => {
    if (state.step >= last) show(0);
    $('play').textContent = '❚❚ pause';
    timer = setInterval(() => (state.step >= last ? pause() : show(state.step + 1)), speed());
  };
  $('play').addEventListener('click', () => (timer ? pause() : play()));
  $('speed').addEventListener('change', () => timer && (pause(), play()));
  slider.addEventListener('input', () => show(Number(slider.value)));
  exag.addEventListener('input', () => setExag(Number(exag.value)));
  $('reset').addEventListener('click', () => scene.resetView());
  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement && e.target.type !== 'range') return;
    if (e.key === 'ArrowRight') show(state.step + 1);
    else if (e.key === 'ArrowLeft') show(state.step - 1);
    else if (e.key === ' ') (timer ? pause() : play());
    else return;
    e.preventDefault();
  });

  const state = { ready: false, step: 0, steps: timeline.length, exaggeration: auto, show, play, pause, scene };
  state.layers = scene.layers;
  state.setLayer = (name, on) => {
    const box = $(`layer-${name}`);
    if (box) box.checked = on;
    scene.setLayer(name, on);
  };
  for (const name of ['planned', 'executed', 'estimate']) {
    const box = $(`layer-${name}`);
    box.addEventListener('change', () => scene.setLayer(name, box.checked));
  }
  window.shoalViewer = state;
  const resize = () => {
    const side = $('side').getBoundingClientRect();
    const covered = host.clientWidth > 900 ? host.clientWidth - side.left : 0;
    scene.resize(host.clientWidth, host.clientHeight, covered);
  };
  window.addEventListener('resize', resize);
  resize();
  setExag(auto);
  show(0);
  scene.resetView();
  const loop = () => {
    scene.render();
    requestAnimationFrame(loop);
  };
  loop();
  state.ready = true;
  document.body.dataset.ready = 'true';
}

try {
  main();
} catch (e) {
  window.shoalFail(e);
}
