// The ellicast live view: the model as a receiver shows it, updated as packets arrive.
// Events from /events: "status" (JSON: packets, points, objects, error, history) and "model"
// (a new GLB at /model.glb). The page never reloads; it swaps the model and keeps the camera.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

// What the page shows, for people who script it (the browser test reads it).
const view = window.ellicastView = {
  connected: false, status: null, modelVersion: 0, shownVersion: 0, triangles: 0,
  loads: 0, loadErrors: 0, frames: 0, fps: 0, problem: null,
  // Per model shown: milliseconds from its "model" event to its first frame drawn, and the
  // seconds after tune-in at which the receiver published it.
  latencies: [], published: [], stages: [],
};
const announced = new Map();  // model version -> (performance.now() of its event, seconds after tune-in)

// A software renderer (SwiftShader, llvmpipe) draws every pixel on the CPU: no multisampling and one
// pixel per CSS pixel there, so that orbiting stays smooth.
function softwareRenderer() {
  const probe = document.createElement('canvas').getContext('webgl2');
  if (!probe) return false;
  const info = probe.getExtension('WEBGL_debug_renderer_info');
  const name = info ? probe.getParameter(info.UNMASKED_RENDERER_WEBGL) : '';
  probe.getExtension('WEBGL_lose_context')?.loseContext();
  return /SwiftShader|llvmpipe|software/i.test(name);
}
const software = softwareRenderer();
view.software = software;
const canvas = document.getElementById('scene');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: !software && window.devicePixelRatio < 2 });
renderer.setPixelRatio(software ? 1 : Math.min(window.devicePixelRatio, 2));
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xdde2e8);  // light models stand out from it
const camera = new THREE.PerspectiveCamera(40, 1, 0.001, 1000);
camera.position.set(0, 0, 3);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = true;
// Light from above and two sides, no environment map: an image-based environment takes seconds to
// prefilter in a software renderer, and the page must show the first picture at once.
const key = new THREE.DirectionalLight(0xffffff, 2.2);
key.position.set(1, 2, 3);
const fill = new THREE.DirectionalLight(0xffffff, 0.8);
fill.position.set(-2, 0.5, -1);
scene.add(key, fill, new THREE.HemisphereLight(0xffffff, 0x8a8a80, 1.2));
// Keep the lights where the camera is, so that every side of the model is lit when orbiting.
scene.add(camera);
camera.add(key);
key.position.set(0.5, 1, 0.6);

let shown = null;      // the glTF scene shown
let framed = false;    // the camera was fitted to the first model
let loading = false;

// Frames are drawn when something changed (the camera, the model, the size), not continuously: the
// page's thread stays free to fetch and parse the next model.
let needsRender = true;
function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
  needsRender = true;
}
window.addEventListener('resize', resize);
resize();

function dispose(object) {
  object.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    const materials = Array.isArray(o.material) ? o.material : o.material ? [o.material] : [];
    for (const m of materials) {
      for (const value of Object.values(m)) if (value && value.isTexture) value.dispose();
      m.dispose();
    }
  });
}

function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  if (box.isEmpty()) return false;
  const center = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2 || 1;
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov) / 2) * 1.05;
  camera.position.copy(center).add(new THREE.Vector3(0.35, 0.25, 1).normalize().multiplyScalar(distance));
  camera.near = distance / 100;
  camera.far = distance * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  controls.update();
  return true;
}

// In a software renderer the physically based shading costs most of a frame: there (or with
// ?shading=lambert) the model is drawn with Lambert materials that keep the colours, textures,
// vertex colours, transparency and sidedness; ?shading=pbr keeps glTF's own.
const shading = new URLSearchParams(location.search).get('shading');
const lambert = shading === 'lambert' || (software && shading !== 'pbr');
view.shading = lambert ? 'lambert' : 'pbr';
function simplifyMaterials(root) {
  root.traverse((o) => {
    if (!o.isMesh) return;
    const swap = (m) => {
      if (!m.isMeshStandardMaterial) return m;
      const l = new THREE.MeshLambertMaterial({
        color: m.color, map: m.map, vertexColors: m.vertexColors, side: m.side, transparent: m.transparent,
        opacity: m.opacity, alphaTest: m.alphaTest, emissive: m.emissive, emissiveMap: m.emissiveMap, name: m.name,
      });
      m.dispose();
      return l;
    };
    o.material = Array.isArray(o.material) ? o.material.map(swap) : swap(o.material);
  });
}
const loader = new GLTFLoader();
async function loadLatest() {
  if (loading) return;
  loading = true;
  try {
    while (view.shownVersion < view.modelVersion) {
      const version = view.modelVersion;
      const t0 = performance.now();
      const response = await fetch(`/model.glb?v=${version}`, { cache: 'no-store' });
      if (!response.ok) throw new Error(`model ${version}: HTTP ${response.status}`);
      const buffer = await response.arrayBuffer();
      const t1 = performance.now();
      const gltf = await loader.parseAsync(buffer, '');
      const t2 = performance.now();
      if (lambert) simplifyMaterials(gltf.scene);
      if (shown) { scene.remove(shown); dispose(shown); }
      shown = gltf.scene;
      scene.add(shown);
      if (!framed) framed = frame(shown);
      needsRender = true;
      let triangles = 0;
      shown.traverse((o) => {
        if (o.isMesh && o.geometry) {
          const g = o.geometry;
          triangles += (g.index ? g.index.count : g.attributes.position.count) / 3;
        }
      });
      view.triangles = triangles;
      view.shownVersion = version;
      const event = announced.get(version);
      if (event) {
        requestAnimationFrame(() => {
          const t3 = performance.now();
          view.latencies.push(t3 - event.at);
          view.published.push(event.seconds);
          view.stages.push({ wait: t0 - event.at, fetch: t1 - t0, parse: t2 - t1, draw: t3 - t2, bytes: buffer.byteLength });
        });
      }
      for (const v of announced.keys()) if (v <= version) announced.delete(v);
      view.loads += 1;
      document.getElementById('model').textContent = `#${version}, ${triangles.toLocaleString('en')} triangles`;
    }
  } catch (e) {
    view.loadErrors += 1;
    showProblem(String(e));
  } finally {
    loading = false;
  }
}

function showProblem(text) {
  view.problem = text;
  const p = document.getElementById('problem');
  p.textContent = text;
  p.hidden = false;
}

const number = (n) => Number(n).toLocaleString('en');
const percent = (x, digits = 1) => `${(100 * x).toFixed(digits)}%`;

function showStatus(s) {
  view.status = s;
  const set = (id, text) => { document.getElementById(id).textContent = text; };
  set('title', s.title || '');
  set('seconds', `${s.seconds.toFixed(1)} s`);
  set('packets', number(s.packets.accepted) + (s.packets.duplicates ? ` (+${number(s.packets.duplicates)} repeats)` : ''));
  const lost = s.packets.lost !== undefined && s.packets.sent
    ? `${number(s.packets.lost)} of ${number(s.packets.sent)} (${percent(s.packets.lost / s.packets.sent)})`
    : `est. ${percent(s.packets.loss_estimate)}`;
  set('lost', lost + (s.packets.damaged ? `, ${number(s.packets.damaged)} damaged` : ''));
  set('base', s.base ? 'whole' : `${number(s.ellipsoids.received)} of ${number(s.ellipsoids.declared)} ellipsoids`);
  const share = s.points.declared ? ` (${percent(s.points.received / s.points.declared)})` : '';
  set('points', `${number(s.points.received)} of ${number(s.points.declared)}${share}`);
  set('inserted', number(s.points.inserted));
  set('held', s.region ? number(s.held) : '–');
  set('exact', `${number(s.exact_objects)} of ${number(s.objects.length)}`);
  const hasReference = s.error.reference !== '';
  set('error-label', hasReference ? 'surface error (RMS)' : 'surface error');
  set('error', s.error.rms_percent === null ? (hasReference ? 'measuring' : 'no reference model')
                                            : `${s.error.rms_percent.toFixed(3)}% of the diagonal`);
  const list = document.getElementById('objects');
  list.replaceChildren(...s.objects.slice(0, 50).map((o) => {
    const li = document.createElement('li');
    const name = document.createElement('span');
    name.textContent = `object ${o.id}: ${number(o.inserted)} / ${number(o.declared)} points`;
    const badge = document.createElement('span');
    badge.className = `badge ${o.state.replace(' ', '-')}`;
    badge.textContent = o.state;
    li.append(name, badge);
    return li;
  }));
  drawSparkline(s.history);
  const connection = document.getElementById('connection');
  connection.textContent = s.final ? (s.complete ? 'complete' : 'ended') : 'live';
  connection.className = `badge ${s.final ? 'finished' : 'live'}`;
}

function drawSparkline(history) {
  const c = document.getElementById('sparkline');
  const g = c.getContext('2d');
  g.clearRect(0, 0, c.width, c.height);
  const samples = history.samples;
  const label = document.getElementById('sparkline-label');
  if (samples.length < 2) { label.textContent = ''; return; }
  const t0 = samples[0][0], t1 = samples[samples.length - 1][0] || 1;
  const top = Math.max(...samples.map((p) => p[1])) || 1;
  g.strokeStyle = '#3a7bd5';
  g.lineWidth = 1.5;
  g.beginPath();
  samples.forEach(([t, v], i) => {
    const x = 2 + (c.width - 4) * (t - t0) / Math.max(t1 - t0, 1e-9);
    const y = c.height - 3 - (c.height - 6) * v / top;
    if (i === 0) g.moveTo(x, y); else g.lineTo(x, y);
  });
  g.stroke();
  label.textContent = history.kind === 'error'
    ? `surface error against time (top ${top.toFixed(3)}%, ${(t1 - t0).toFixed(1)} s)`
    : `points shown against time (top ${top.toFixed(1)}%, ${(t1 - t0).toFixed(1)} s)`;
}

function connect() {
  const events = new EventSource('/events');
  events.addEventListener('open', () => { view.connected = true; });
  events.addEventListener('status', (e) => showStatus(JSON.parse(e.data)));
  events.addEventListener('model', (e) => {
    const m = JSON.parse(e.data);
    if (m.version > view.modelVersion) {
      announced.set(m.version, { at: performance.now(), seconds: m.seconds });
      view.modelVersion = m.version;
      loadLatest();
    }
  });
  events.addEventListener('problem', (e) => showProblem(JSON.parse(e.data)));
  events.addEventListener('error', () => {
    view.connected = false;
    const connection = document.getElementById('connection');
    if (!connection.classList.contains('finished')) {
      connection.textContent = 'reconnecting';
      connection.className = 'badge waiting';
    }
  });
}
connect();

// Refinement where the viewer looks: the camera goes to the receiver (debounced), which inserts only
// the points in view and holds the others until the view turns to them.
const refine = document.getElementById('refine-view');
let cameraTimer = null;
function sendCamera() {
  if (!refine.checked) return;
  clearTimeout(cameraTimer);
  cameraTimer = setTimeout(() => {
    const p = camera.position, t = controls.target, f = (v) => v.toPrecision(7);
    const query = `eye=${f(p.x)},${f(p.y)},${f(p.z)}&target=${f(t.x)},${f(t.y)},${f(t.z)}` +
                  `&fov=${f(camera.fov)}&aspect=${f(camera.aspect)}`;
    fetch(`/camera?${query}`, { cache: 'no-store' }).catch(() => {});
  }, 250);
}
controls.addEventListener('change', sendCamera);
refine.addEventListener('change', () => {
  if (refine.checked) sendCamera();
  else fetch('/camera?off', { cache: 'no-store' }).catch(() => {});
});
view.setPixelRatio = (r) => { renderer.setPixelRatio(r); resize(); };
view.refineWhereILook = (on) => { refine.checked = on; refine.dispatchEvent(new Event('change')); };

controls.addEventListener('change', () => { needsRender = true; });
let fpsFrames = 0, fpsSince = performance.now();
function animate() {
  requestAnimationFrame(animate);
  controls.update();  // damping: keeps moving (and asking for frames) a moment after the mouse stops
  const now = performance.now();
  if (needsRender) {
    needsRender = false;
    renderer.render(scene, camera);
    view.frames += 1;
    fpsFrames += 1;
  }
  if (now - fpsSince >= 1000) {
    view.fps = fpsFrames * 1000 / (now - fpsSince);
    document.getElementById('fps').textContent = `${view.fps.toFixed(0)} frames/s drawn${software ? ' (software renderer)' : ''}`;
    fpsFrames = 0;
    fpsSince = now;
  }
}
animate();

// Frames a second while orbiting for `ms` milliseconds (a full turn), drawing every frame.
view.measureOrbit = (ms = 2000) => new Promise((resolve) => {
  const start = performance.now(), offset = camera.position.clone().sub(controls.target);
  let frames = 0;
  function step() {
    const t = performance.now() - start;
    const angle = 2 * Math.PI * t / ms;
    const turned = offset.clone().applyAxisAngle(new THREE.Vector3(0, 1, 0), angle);
    camera.position.copy(controls.target).add(turned);
    camera.lookAt(controls.target);
    renderer.render(scene, camera);
    frames += 1;
    if (t < ms) requestAnimationFrame(step);
    else {
      camera.position.copy(controls.target).add(offset);
      camera.lookAt(controls.target);
      needsRender = true;
      resolve(frames * 1000 / t);
    }
  }
  requestAnimationFrame(step);
});
