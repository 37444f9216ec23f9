'use strict';
// lagrange view's page: draws ROBOT_DESCRIPTION's frames and shapes with
// three.js, the arm at PLANT_TRUTH's q, a ghost at CONTROL_COMMAND's
// q_desired, rotor pointers at PLANT_MOTOR's angles, and plots of |q~| and
// the torques. A log comes whole from /api/log and plays on the page's own
// clock; a running scenario streams from /api/live (Server-Sent Events).
// window.lagrangeViewer is what the browser tests read and drive.
//
// The ready signal: <body data-ready="true"> once the first frame of the
// arm and its plots is on the screen (set an animation frame after it was
// drawn, so the browser has presented it), "error" when the run cannot be
// loaded. A headless screenshot waits for it (docs/viewer.md).

const ARM_COLOR = 0x4a78b8, GHOST_COLOR = 0x999999, TIP_COLOR = 0xff00ff, ROTOR_COLOR = 0xf08c00;

// Live, the page keeps the newest frames only (about 15 minutes of a 1 kHz
// run at the server's 200 frames per 100 ms).
const MAX_LIVE_FRAMES = 200000;

const view = {
  mode: null,            // 'log' or 'live'
  description: null,
  frames: {t: [], q: [], q_desired: [], motor: [], tau: [], error_norm: []},
  torques: [],           // frames.tau by joint, for the plot
  envelope: null,        // a strided log's min/max between the frames sent (plots.js)
  t: 0,                  // the time drawn [s]
  index: -1,             // the frame drawn: the last with frames.t <= t
  playing: false,
  speed: 1,
  follow: true,          // live: draw the newest frame
  lastWall: null,        // performance.now() of the previous animation frame, while playing
  arm: null, ghost: null,
  dirty: true,           // something changed since the last render: only then is the scene drawn again
  errors: [],
  presentedT: null,      // the time of the frame last on the screen (an animation frame after its draw)
};

function status(text) { document.getElementById('status').textContent = text; }
window.addEventListener('error', (e) => status('error: ' + e.message));

// --- the scene ---------------------------------------------------------------

const container = document.getElementById('scene');
// Without WebGL (disabled, or a headless browser without a GPU fallback) the
// plots and controls still work; the page says why there is no arm.
let renderer = null;
try {
  renderer = new THREE.WebGLRenderer({antialias: true});
  renderer.setPixelRatio(1);
  container.appendChild(renderer.domElement);
} catch (e) {
  container.textContent = 'No 3D view: this browser cannot create a WebGL context (' + e.message +
      '). The plots below still follow the run.';
}
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
scene.add(new THREE.AmbientLight(0xffffff, 0.55));
const sun = new THREE.DirectionalLight(0xffffff, 0.6);
sun.position.set(1, 2, 3);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
const controls = renderer ? new THREE.OrbitControls(camera, renderer.domElement) : null;
if (controls) controls.addEventListener('change', () => { view.dirty = true; });

function resize() {
  if (!renderer) return;
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h);
  view.dirty = true;
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);

const vec = (a) => new THREE.Vector3(a[0], a[1], a[2]);
const quat = (a) => new THREE.Quaternion(a[1], a[2], a[3], a[0]);  // the message's (w, x, y, z)

function shapeGeometry(type, size) {
  if (type === 0) return new THREE.BoxBufferGeometry(size[0], size[1], size[2]);
  if (type === 1) {  // along its local z; three's cylinders are along y
    const g = new THREE.CylinderBufferGeometry(size[0], size[0], size[1], 24);
    g.rotateX(Math.PI / 2);
    return g;
  }
  return new THREE.SphereBufferGeometry(size[0], 24, 16);
}

// One arm: an Object3D per frame origin, a child turned by the joint angle,
// the shapes on the frames. Poses follow robot_description_t's rule.
function buildArm(d, material, withExtras) {
  const root = new THREE.Group();
  const joints = [], origins = [], rotors = [];
  const holder = (frame) => frame < 0 ? root : joints[frame];
  for (let i = 0; i < d.frame_parent.length; i++) {
    const origin = new THREE.Object3D();
    origin.position.copy(vec(d.frame_xyz[i]));
    origin.quaternion.copy(quat(d.frame_quat[i]));
    holder(d.frame_parent[i]).add(origin);
    const joint = new THREE.Object3D();
    origin.add(joint);
    origins.push(origin);
    joints.push(joint);
  }
  let tipRadius = 0.02;
  for (let s = 0; s < d.shape_frame.length; s++) {
    const mesh = new THREE.Mesh(shapeGeometry(d.shape_type[s], d.shape_size[s]), material);
    mesh.position.copy(vec(d.shape_xyz[s]));
    mesh.quaternion.copy(quat(d.shape_quat[s]));
    holder(d.shape_frame[s]).add(mesh);
    if (d.shape_type[s] === 2 && d.shape_frame[s] === d.tip_frame) tipRadius = d.shape_size[s][0];
  }
  let tip = null;
  if (withExtras) {
    // Unlit and drawn over everything: one exact colour where the tip is.
    tip = new THREE.Mesh(new THREE.SphereBufferGeometry(tipRadius * 0.8, 24, 16),
                         new THREE.MeshBasicMaterial({color: TIP_COLOR, depthTest: false}));
    tip.renderOrder = 10;
    tip.position.copy(vec(d.tip_xyz));
    holder(d.tip_frame).add(tip);
    if (d.flexible) {
      // A rotor pointer per joint, on the frame's origin (it does not turn
      // with the link): at the motor angle about the same axis.
      for (let i = 0; i < joints.length; i++) {
        if (d.frame_joint[i] < 0) continue;
        const rotor = new THREE.Object3D();
        const bar = new THREE.Mesh(new THREE.BoxBufferGeometry(tipRadius * 0.4, tipRadius * 3.2, tipRadius * 0.4),
                                   new THREE.MeshBasicMaterial({color: ROTOR_COLOR, depthTest: false}));
        bar.renderOrder = 9;
        // Points where the link points at angle 0 when the arm is planar (-y), else along x.
        const along = d.plane_normal.some((v) => v !== 0) ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(1, 0, 0);
        bar.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), along);
        bar.position.copy(along.clone().multiplyScalar(tipRadius * 1.6));
        rotor.add(bar);
        origins[i].add(rotor);
        rotors.push({frame: i, object: rotor});
      }
    }
  }
  const axes = d.frame_axis.map((a) => vec(a).normalize());
  function pose(q, motor) {
    for (let i = 0; i < joints.length; i++) {
      const k = d.frame_joint[i];
      if (k >= 0 && q && q[k] !== null) joints[i].quaternion.setFromAxisAngle(axes[i], q[k]);
    }
    for (const r of rotors) {
      const k = d.frame_joint[r.frame];
      if (motor && motor[k] !== undefined && motor[k] !== null) {
        r.object.visible = true;
        r.object.quaternion.setFromAxisAngle(axes[r.frame], motor[k]);
      } else {
        r.object.visible = false;
      }
    }
  }
  return {root, pose, tip};
}

function reach(d) {
  let r = 0;
  for (const p of d.frame_xyz) r += vec(p).length();
  return Math.max(r + vec(d.tip_xyz).length(), 0.1);
}

function describe(d) {
  view.description = d;
  view.arm = buildArm(d, new THREE.MeshLambertMaterial({color: ARM_COLOR}), true);
  view.ghost = buildArm(d, new THREE.MeshBasicMaterial({color: GHOST_COLOR, transparent: true, opacity: 0.3,
                                                         depthWrite: false}), false);
  scene.add(view.ghost.root);
  scene.add(view.arm.root);
  const r = reach(d), up = vec(d.up).normalize(), normal = vec(d.plane_normal);
  camera.up.copy(up);
  if (normal.length() > 0) {
    camera.position.copy(normal.normalize().multiplyScalar(3.2 * r));  // face the plane of motion
  } else {
    const side = Math.abs(up.z) > 0.9 ? new THREE.Vector3(1, 0.8, 0) : new THREE.Vector3(0.8, 0, 1);
    camera.position.copy(side.normalize().multiplyScalar(2.6 * r).add(up.clone().multiplyScalar(1.2 * r)));
  }
  if (controls) {
    controls.target.set(0, 0, 0);
    controls.update();
  }
  view.dirty = true;
  const names = d.joint_names.join(', ');
  document.getElementById('legend').title = d.kind + ': ' + names;
  // The legend names only what this arm has: rotors on elastic joints alone.
  document.getElementById('legend-rotor').hidden = !d.flexible;
  document.getElementById('torque-plot').title =
      d.joint_names.map((name, k) => 'τ' + (k + 1) + ': ' + name).join('\n');
}

// --- frames and time -----------------------------------------------------------

const errorPlot = new TimePlot(document.getElementById('error-plot'), '|q~| = |q - q_desired| [rad], log scale', true);
const torquePlot = new TimePlot(document.getElementById('torque-plot'), 'applied torque [N m]', false);
const seek = document.getElementById('seek');

function appendFrames(f) {
  const all = view.frames;
  for (const key of Object.keys(all)) for (const v of f[key]) all[key].push(v);
  for (const row of f.tau) {
    row.forEach((v, k) => {
      if (view.torques.length <= k) view.torques.push([]);
      view.torques[k].push(v);
    });
  }
  const excess = all.t.length - MAX_LIVE_FRAMES;
  if (view.mode === 'live' && excess > 0) {
    for (const key of Object.keys(all)) all[key].splice(0, excess);
    for (const column of view.torques) column.splice(0, excess);
    view.index = Math.max(view.index - excess, 0);
  }
  const n = all.t.length;
  if (n === 0) return;
  seek.min = all.t[0];
  seek.max = all.t[n - 1];
  const env = view.envelope;  // a log sent as every k-th frame: the peaks between them
  errorPlot.setData(all.t, [all.error_norm], ['|q~|'], env ? {lo: [env.error_min], hi: [env.error_max]} : null);
  torquePlot.setData(all.t, view.torques, view.torques.map((_, k) => 'τ' + (k + 1)),
                     env ? {lo: env.tauMin, hi: env.tauMax} : null);
  view.dirty = true;
}

// The last frame at or before t (the first when t precedes them all). A
// nanosecond of slack: the seek bar gives back 0.35 for a tick logged at
// 0.35000000000000003 (a multiple of the period, rounded).
function frameIndex(time) {
  const t = time + 1e-9;
  const ts = view.frames.t;
  let lo = 0, hi = ts.length - 1;
  if (hi < 0) return -1;
  if (t <= ts[0]) return 0;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (ts[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}

function setTime(t) {
  const ts = view.frames.t;
  if (ts.length === 0) return;
  view.t = Math.min(Math.max(t, ts[0]), ts[ts.length - 1]);
  view.index = frameIndex(view.t);
  view.dirty = true;
}

function draw() {
  const i = view.index;
  if (view.arm && i >= 0) {
    const f = view.frames;
    view.arm.pose(f.q[i], f.motor[i]);
    view.ghost.root.visible = f.q_desired[i] !== null;
    view.ghost.pose(f.q_desired[i], null);
    document.getElementById('time').textContent = 't = ' + view.t.toFixed(3) + ' s';
    if (document.activeElement !== seek) seek.value = view.t;
    errorPlot.cursor = view.t;
    torquePlot.cursor = view.t;
  }
  errorPlot.draw();
  torquePlot.draw();
  if (renderer) {
    controls.update();
    renderer.render(scene, camera);
  }
  if (view.arm && i >= 0) {
    const drawnT = view.t;
    requestAnimationFrame(() => {
      view.presentedT = drawnT;
      document.body.dataset.ready = 'true';
    });
  }
}

function animate(now) {
  const ts = view.frames.t;
  if (view.playing && ts.length > 0) {
    if (view.mode === 'live' && view.follow) {
      setTime(ts[ts.length - 1]);
    } else if (view.lastWall !== null) {
      setTime(view.t + (now - view.lastWall) / 1000 * view.speed);
      if (view.mode === 'log' && view.t >= ts[ts.length - 1]) setPlaying(false);  // the end of the log
    }
    view.lastWall = now;
  }
  // Drawn only when something changed: an idle page costs no CPU (a
  // software-rendered WebGL page redrawn 60 times a second keeps a core busy).
  if (view.dirty) {
    view.dirty = false;
    draw();
  }
  requestAnimationFrame(animate);
}

function setPlaying(on) {
  view.playing = on;
  view.lastWall = null;
  if (on && view.mode === 'log' && view.t >= view.frames.t[view.frames.t.length - 1]) setTime(view.frames.t[0]);
  document.getElementById('play').textContent = on ? 'Pause' : 'Play';
}

document.getElementById('play').addEventListener('click', () => {
  if (view.mode === 'live' && !view.playing) view.follow = true;  // play again: back to the newest
  setPlaying(!view.playing);
});
document.getElementById('speed').addEventListener('change', (e) => {
  view.speed = Number(e.target.value);
  view.lastWall = null;
});
// Space plays and pauses, as in a video player (not while a control has the focus).
window.addEventListener('keydown', (e) => {
  if (e.key !== ' ' || ['BUTTON', 'SELECT', 'INPUT'].includes(document.activeElement.tagName)) return;
  e.preventDefault();
  document.getElementById('play').click();
});
seek.addEventListener('input', () => {
  view.follow = false;
  setTime(Number(seek.value));
  view.lastWall = null;
});

// --- sources -----------------------------------------------------------------------

async function start() {
  resize();
  const session = await (await fetch('api/session')).json();
  view.mode = session.mode;
  document.getElementById('source').textContent = (session.mode === 'live' ? 'live: ' : 'log: ') + session.source;
  if (session.mode === 'log') {
    const log = await (await fetch('api/log')).json();
    if (log.envelope) {
      const byJoint = (rows) => rows.length ? rows[0].map((_, k) => rows.map((r) => r[k])) : [];
      view.envelope = {error_min: log.envelope.error_min, error_max: log.envelope.error_max,
                       tauMin: byJoint(log.envelope.tau_min), tauMax: byJoint(log.envelope.tau_max)};
    }
    if (log.verdict) {  // summary.json's verdict, as the run's last block says it
      const line = document.getElementById('verdict');
      line.textContent = log.verdict.headline;
      line.className = log.verdict.met ? 'met' : 'not-met';
      line.hidden = false;
    }
    describe(log.description);
    appendFrames(log.frames);
    setTime(view.frames.t[0]);
    if (log.warnings.length) status(log.warnings.join('\n'));
    document.getElementById('seek').title = log.stride > 1 ? 'every ' + log.stride + ' ticks of the log' : '';
  } else {
    const events = new EventSource('api/live');
    events.addEventListener('description', (e) => describe(JSON.parse(e.data)));
    events.addEventListener('frames', (e) => {
      appendFrames(JSON.parse(e.data));
      if (view.index < 0) setTime(view.frames.t[0]);
    });
    events.onerror = () => status('the live stream was interrupted; the viewer reconnects while the server runs');
    events.onopen = () => status('');
    setPlaying(true);
  }
  requestAnimationFrame(animate);
}

// What the browser tests read and drive (tests/integration/view_test.cpp).
window.lagrangeViewer = {
  ready: false,  // the source is loaded (its first frame on the screen: body[data-ready])
  state() {
    return {mode: view.mode, t: view.t, index: view.index, frames: view.frames.t.length, playing: view.playing,
            speed: view.speed, follow: view.follow, described: view.description !== null,
            tEnd: view.frames.t.length ? view.frames.t[view.frames.t.length - 1] : null,
            wall: view.lastWall, frameT: view.index >= 0 ? view.frames.t[view.index] : null,
            q: view.index >= 0 ? view.frames.q[view.index] : null,
            q_desired: view.index >= 0 ? view.frames.q_desired[view.index] : null,
            motor: view.index >= 0 ? view.frames.motor[view.index] : null, presentedT: view.presentedT};
  },
  // The range each plot draws, in its data's units ([lo, hi]; null before data).
  plotExtents() {
    return {error: errorPlot.extent(), torque: torquePlot.extent()};
  },
  // A base-frame point in the page's CSS pixels, through the camera drawn.
  project(p) {
    if (!renderer) return null;
    const v = new THREE.Vector3(p[0], p[1], p[2]).project(camera);
    const box = renderer.domElement.getBoundingClientRect();
    return [box.left + (v.x + 1) / 2 * box.width, box.top + (1 - v.y) / 2 * box.height];
  },
};

start().then(() => { window.lagrangeViewer.ready = true; },
             (e) => {
               status('cannot load the run: ' + e.message);
               document.body.dataset.ready = 'error';
             });
