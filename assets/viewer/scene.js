// The three.js scene of the shoal viewer: the seafloor mesh, the vehicles' paths, their
// markers and the acoustic links at the current step. World axes are the plan's: x east,
// y north, z up (metres, the origin moved to the centre of the floor shown), with every z
// multiplied by the vertical exaggeration.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export const COLORS = {
  usv: '#ffffff',
  a2u: '#8fd8ff', // acoustic links AUV–USV: light blue
  a2a: '#ffd21f', // acoustic links AUV–AUV: yellow
  background: '#0b1626',
  surface: '#9fd0ff',
};

// AUV i's colour: its figures' colour, tinted for the dark background by the planner
// (`viewer::data::auv_colour`).
export function auvColor(data, i) {
  return data.auv_colours[i] ?? '#aaaaaa';
}

// Depth colours, deepest first (t = 0) to shallowest (t = 1).
export const DEPTH_STOPS = ['#0d1b4c', '#1d4e89', '#2a8c9e', '#6fbf97', '#d9d29b'];

function depthColor(t, out) {
  const stops = DEPTH_STOPS.map((c) => new THREE.Color(c));
  const u = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(u), stops.length - 2);
  return out.copy(stops[i]).lerp(stops[i + 1], u - i);
}

function decodeFloor(f) {
  const bin = atob(f.z);
  const z = new Float32Array(f.nx * f.ny);
  const nodata = new Uint8Array(f.nx * f.ny);
  const step = f.z_hi > f.z_lo ? (f.z_hi - f.z_lo) / 65534 : 0;
  for (let k = 0; k < z.length; k++) {
    const q = bin.charCodeAt(2 * k) | (bin.charCodeAt(2 * k + 1) << 8);
    nodata[k] = q === 65535 ? 1 : 0;
    z[k] = q === 65535 ? f.z_hi : f.z_lo + q * step;
  }
  return { z, nodata };
}

function floorMesh(f, cx, cy) {
  const { z, nodata } = decodeFloor(f);
  const pos = new Float32Array(3 * z.length);
  const col = new Float32Array(3 * z.length);
  const c = new THREE.Color();
  const span = f.z_hi - f.z_lo || 1;
  for (let j = 0; j < f.ny; j++) {
    for (let i = 0; i < f.nx; i++) {
      const k = j * f.nx + i;
      pos.set([f.x0 + i * f.dx - cx, f.y0 + j * f.dy - cy, z[k]], 3 * k);
      if (nodata[k]) c.set('#555555');
      else depthColor((z[k] - f.z_lo) / span, c);
      col.set([c.r, c.g, c.b], 3 * k);
    }
  }
  const index = [];
  for (let j = 0; j + 1 < f.ny; j++) {
    for (let i = 0; i + 1 < f.nx; i++) {
      const a = j * f.nx + i, b = a + 1, d = a + f.nx, e = d + 1;
      if (nodata[a] || nodata[b] || nodata[d] || nodata[e]) continue;
      index.push(a, b, e, a, e, d);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('color', new THREE.BufferAttribute(col, 3));
  g.setIndex(index);
  g.computeVertexNormals();
  const m = new THREE.MeshLambertMaterial({
    vertexColors: true,
    side: THREE.DoubleSide,
    polygonOffset: true,
    polygonOffsetFactor: 1,
    polygonOffsetUnits: 1,
  });
  return new THREE.Mesh(g, m);
}

const UP = new THREE.Vector3(0, 1, 0);

// Places a unit cylinder (axis y, height 1) between a and b with radius r.
function segmentMatrix(a, b, r, m) {
  const d = new THREE.Vector3().subVectors(b, a);
  const len = d.length();
  const q = new THREE.Quaternion();
  if (len > 0) q.setFromUnitVectors(UP, d.clone().divideScalar(len));
  const mid = new THREE.Vector3().addVectors(a, b).multiplyScalar(0.5);
  return m.compose(mid, q, new THREE.Vector3(r, Math.max(len, 1e-6), r));
}

export class MissionScene {
  // data: the plan's viewer data; timeline: [{w, k}] per global step; host: the element.
  constructor(data, timeline, host) {
    this.data = data;
    this.timeline = timeline;
    const f = data.floor;
    this.cx = f.x0 + 0.5 * (f.nx - 1) * f.dx;
    this.cy = f.y0 + 0.5 * (f.ny - 1) * f.dy;
    this.extent = Math.max((f.nx - 1) * f.dx, (f.ny - 1) * f.dy, 1);
    this.radius = this.extent / 600;
    this.exaggeration = 1;
    this.step = 0;

    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    host.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(COLORS.background);
    this.scene.add(new THREE.HemisphereLight('#dbe9ff', '#20252b', 1.6));
    const sun = new THREE.DirectionalLight('#ffffff', 2.2);
    sun.position.set(-0.6, 0.8, 1.2);
    this.scene.add(sun);

    this.camera = new THREE.PerspectiveCamera(45, 1, this.extent / 1000, this.extent * 20);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.enableDamping = true;
    this.controls.dampingFactor = 0.12;

    this.floor = floorMesh(f, this.cx, this.cy);
    this.scene.add(this.floor);
    this.surface = new THREE.Mesh(
      new THREE.PlaneGeometry((f.nx - 1) * f.dx, (f.ny - 1) * f.dy),
      new THREE.MeshBasicMaterial({
        color: COLORS.surface, transparent: true, opacity: 0.06, depthWrite: false,
        side: THREE.DoubleSide,
      }),
    );
    this.scene.add(this.surface);

    this.vehicles = this.buildVehicles();
    this.links = this.buildLinkPool();
    // With a simulation: each AUV's executed track (a tube darker and thicker than the planned
    // path) and the estimate's track (dots); the markers follow the executed track.
    this.layers = { planned: true, executed: !!data.sim, estimate: !!data.sim };
    this.tracks = data.sim ? this.buildTracks() : [];
  }

  buildTracks() {
    const d = this.data;
    const s = d.sim;
    const segments = Math.max(s.times.length - 1, 1);
    const cyl = new THREE.CylinderGeometry(1, 1, 1, 8, 1, true);
    const tracks = [];
    for (let i = 0; i < d.auvs; i++) {
      const base = new THREE.Color(auvColor(d, i));
      const dark = base.clone().multiplyScalar(0.45);
      const mat = new THREE.MeshLambertMaterial({ color: dark, emissive: dark, emissiveIntensity: 0.4 });
      const exec = new THREE.InstancedMesh(cyl, mat, segments);
      exec.count = s.times.length - 1;
      // no estimate when every estimator failed: the executed tracks alone
      const est = s.estimate ? s.estimate.position[i] : [];
      const pos = new Float32Array(3 * est.length);
      est.forEach((p, e) => pos.set([p[0] - this.cx, p[1] - this.cy, p[2]], 3 * e));
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      const light = base.clone().lerp(new THREE.Color('#ffffff'), 0.3);
      const dots = new THREE.Points(g, new THREE.PointsMaterial({ color: light, size: 3, sizeAttenuation: false }));
      for (const o of [exec, dots]) o.frustumCulled = false;
      this.scene.add(exec, dots);
      tracks.push({ exec, dots, executed: s.executed[i], estimate: est });
    }
    return tracks;
  }

  // Shows or hides a layer: 'planned' (the planned paths), 'executed' (the executed tracks;
  // the markers follow them while shown) or 'estimate' (the estimated tracks).
  setLayer(name, on) {
    this.layers[name] = on;
    for (const v of this.vehicles) for (const m of [v.done, v.todo, v.joints]) m.visible = this.layers.planned;
    for (const t of this.tracks) {
      t.exec.visible = this.layers.executed;
      t.dots.visible = this.layers.estimate;
    }
    this.setStep(this.step);
  }

  // Seconds since the start of the mission at global step g.
  timeAt(g) {
    const { w, k } = this.timeline[g];
    return this.data.windows[w].start_time + k * this.data.dt;
  }

  // Position on `track` ([epoch] of [x, y, z]) at time t, linear between the sim's epochs.
  simAt(track, t) {
    const T = this.data.sim.times;
    const n = T.length - 1;
    if (n <= 0 || t <= T[0]) return track[0];
    if (t >= T[n]) return track[n];
    let lo = 0, hi = n;
    while (hi - lo > 1) {
      const m = (lo + hi) >> 1;
      if (T[m] <= t) lo = m;
      else hi = m;
    }
    const u = (t - T[lo]) / (T[hi] - T[lo]);
    const a = track[lo], b = track[hi];
    return [0, 1, 2].map((j) => a[j] + u * (b[j] - a[j]));
  }

  // One entry per vehicle: its points along the timeline and its meshes.
  buildVehicles() {
    const d = this.data;
    const list = [{ name: 'USV', color: COLORS.usv, usv: true }];
    for (let i = 0; i < d.auvs; i++) list.push({ name: `AUV ${i}`, color: auvColor(d, i), auv: i });
    const segments = Math.max(this.timeline.length - 1, 1);
    const cyl = new THREE.CylinderGeometry(1, 1, 1, 10, 1, true);
    const ball = new THREE.SphereGeometry(1, 18, 12);
    for (const v of list) {
      v.points = this.timeline.map(({ w, k }) => {
        const win = d.windows[w];
        return v.usv ? [win.usv[k][0], win.usv[k][1], 0] : win.auvs[v.auv][k];
      });
      const lit = new THREE.MeshLambertMaterial({ color: v.color, emissive: v.color, emissiveIntensity: 0.35 });
      const faint = new THREE.MeshBasicMaterial({ color: v.color, transparent: true, opacity: 0.35 });
      v.done = new THREE.InstancedMesh(cyl, lit, segments);
      v.todo = new THREE.InstancedMesh(cyl, faint, segments);
      v.joints = new THREE.InstancedMesh(ball, lit, this.timeline.length);
      v.marker = new THREE.Mesh(v.usv ? new THREE.ConeGeometry(1, 2.2, 4) : ball, lit);
      for (const m of [v.done, v.todo, v.joints]) m.frustumCulled = false;
      this.scene.add(v.done, v.todo, v.joints, v.marker);
    }
    return list;
  }

  buildLinkPool() {
    const geo = new THREE.CylinderGeometry(1, 1, 1, 8, 1, true);
    const mats = {
      a2u: new THREE.MeshBasicMaterial({ color: COLORS.a2u }),
      a2a: new THREE.MeshBasicMaterial({ color: COLORS.a2a }),
    };
    const n = Math.max(this.data.auvs, 1);
    const pool = { a2u: [], a2a: [] };
    for (const kind of ['a2u', 'a2a']) {
      for (let i = 0; i < n; i++) {
        const m = new THREE.Mesh(geo, mats[kind]);
        m.matrixAutoUpdate = false;
        m.visible = false;
        this.scene.add(m);
        pool[kind].push(m);
      }
    }
    return pool;
  }

  world(p) {
    return new THREE.Vector3(p[0] - this.cx, p[1] - this.cy, p[2] * this.exaggeration);
  }

  setExaggeration(e) {
    this.exaggeration = e;
    this.floor.scale.z = e;
    const r = this.radius;
    const m = new THREE.Matrix4();
    for (const v of this.vehicles) {
      const pts = v.points.map((p) => this.world(p));
      for (let s = 0; s + 1 < pts.length; s++) {
        v.done.setMatrixAt(s, segmentMatrix(pts[s], pts[s + 1], r, m));
        v.todo.setMatrixAt(s, segmentMatrix(pts[s], pts[s + 1], 0.6 * r, m));
      }
      pts.forEach((p, s) => v.joints.setMatrixAt(s, m.makeScale(r, r, r).setPosition(p)));
      for (const im of [v.done, v.todo, v.joints]) im.instanceMatrix.needsUpdate = true;
      v.marker.scale.setScalar((v.usv ? 5 : 3.5) * r);
    }
    for (const t of this.tracks) {
      const pts = t.executed.map((p) => this.world(p));
      for (let s = 0; s + 1 < pts.length; s++) t.exec.setMatrixAt(s, segmentMatrix(pts[s], pts[s + 1], 1.3 * r, m));
      t.exec.instanceMatrix.needsUpdate = true;
      t.dots.scale.z = e;
    }
    this.setStep(this.step);
  }

  // Shows the mission at global step g: travelled paths, markers and that step's links.
  setStep(g) {
    this.step = g;
    const { w, k } = this.timeline[g];
    for (const v of this.vehicles) {
      v.done.count = g;
      v.joints.count = g + 1;
      const track = this.layers.executed && !v.usv && this.tracks[v.auv];
      v.marker.position.copy(this.world(track ? this.simAt(track.executed, this.timeAt(g)) : v.points[g]));
      if (v.usv) v.marker.rotation.set(Math.PI / 2, 0, 0);
    }
    for (const kind of ['a2u', 'a2a']) for (const m of this.links[kind]) m.visible = false;
    const win = this.data.windows[w];
    const used = { a2u: 0, a2a: 0 };
    const pos = (i) => (i === null ? [win.usv[k][0], win.usv[k][1], 0] : win.auvs[i][k]);
    for (const [a, b] of win.links[k] || []) {
      const kind = b === null ? 'a2u' : 'a2a';
      const m = this.links[kind][used[kind]++];
      if (!m) continue;
      segmentMatrix(this.world(pos(a)), this.world(pos(b)), 0.8 * this.radius, m.matrix);
      m.visible = true;
    }
  }

  // Looks at the mission from the south-south-west, above, framing the sphere around every
  // vehicle's path down to the deepest floor shown.
  resetView() {
    const lo = new THREE.Vector3(Infinity, Infinity, this.data.floor.z_lo * this.exaggeration);
    const hi = new THREE.Vector3(-Infinity, -Infinity, 0);
    for (const v of this.vehicles) for (const p of v.points) {
      const q = this.world(p);
      lo.min(q);
      hi.max(q);
    }
    const centre = lo.clone().add(hi).multiplyScalar(0.5);
    const radius = Math.max(0.5 * lo.distanceTo(hi), 0.1 * this.extent);
    const aspect = this.viewWidth / Math.max(this.viewHeight, 1);
    const vfov = (this.camera.fov * Math.PI) / 180;
    const hfov = 2 * Math.atan(Math.tan(vfov / 2) * aspect);
    const dist = (0.95 * radius) / Math.sin(Math.min(vfov, hfov) / 2);
    const dir = new THREE.Vector3(-0.25, -0.8, 0.62).normalize().multiplyScalar(dist);
    this.controls.target.copy(centre);
    this.camera.position.copy(centre).add(dir);
    this.controls.update();
  }

  // The canvas fills the window; `offset` pixels on the right are covered by a panel, so the
  // view is centred in the rest.
  resize(width, height, offset = 0) {
    this.viewWidth = width - offset;
    this.viewHeight = height;
    this.renderer.setSize(width, height);
    this.camera.aspect = width / Math.max(height, 1);
    this.camera.setViewOffset(width, height, offset / 2, 0, width, height);
    this.camera.updateProjectionMatrix();
  }

  render() {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
  }
}
