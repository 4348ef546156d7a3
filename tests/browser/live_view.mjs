// The live view in a real browser: `ellicast view` plays a recording at 30% loss while a headless
// Chromium shows the page; screenshots at three moments (the first picture, a refined one with more
// points shown, the exact model) are checked for a silhouette where the model is, that stays put and
// grows more detailed, and the panel's counts are checked against the server's status.
//
// usage: node live_view.mjs ELLICAST STREAM.ellc REFERENCE_MODEL OUTDIR NODE_MODULES
// Exit 0: passed; 1: failed (each failure named); 77: skipped (no Chromium or no ws module).
import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import zlib from 'node:zlib';

const [ellicast, stream, reference, outdir, nodeModules] = process.argv.slice(2);
if (!nodeModules) {
  console.error('usage: node live_view.mjs ELLICAST STREAM.ellc REFERENCE_MODEL OUTDIR NODE_MODULES');
  process.exit(2);
}
const SKIP = 77;

function findChromium() {
  const candidates = [process.env.CHROMIUM, 'chromium-headless-shell', 'chromium', 'chromium-browser', 'google-chrome'];
  for (const c of candidates) {
    if (!c) continue;
    if (c.includes('/')) { if (fs.existsSync(c)) return c; continue; }
    for (const dir of (process.env.PATH || '').split(':')) {
      const p = path.join(dir, c);
      if (fs.existsSync(p)) return p;
    }
  }
  return null;
}
const chromiumPath = findChromium();
if (!chromiumPath) {
  console.log('SKIP: no Chromium (chromium-headless-shell or chromium) is installed; scripts/setup.sh installs it');
  process.exit(SKIP);
}
let WebSocket;
try {
  WebSocket = createRequire(path.resolve(nodeModules, 'noop.js'))('ws');
} catch {
  console.log(`SKIP: the ws module is not in ${nodeModules}; scripts/setup.sh installs it`);
  process.exit(SKIP);
}

fs.mkdirSync(outdir, { recursive: true });
const failures = [];
const check = (ok, what) => { if (!ok) failures.push(what); console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
const children = [];
// Each child leads a process group of its own (Debian's chromium-headless-shell is a script that
// starts the browser as its child): the whole group is killed.
function cleanup() { for (const c of children) { try { process.kill(-c.pid, 'SIGKILL'); } catch {} } }
process.on('exit', cleanup);
const deadline = setTimeout(() => { console.error('FAIL: the test took more than 240 s'); cleanup(); process.exit(1); }, 240000);

// Reads a process's stderr until a line matches; resolves with the match.
function waitForLine(child, pattern, what, ms = 60000) {
  return new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`${what}: nothing after ${ms} ms; stderr: ${text.slice(-2000)}`)), ms);
    child.stderr.on('data', (d) => {
      text += d.toString();
      const m = text.match(pattern);
      if (m) { clearTimeout(timer); resolve(m); }
    });
    child.on('exit', (code) => reject(new Error(`${what}: exited with ${code}; stderr: ${text.slice(-2000)}`)));
  });
}

// --- PNG decoding (8-bit RGB/RGBA, not interlaced: what Chromium writes) ---
function decodePng(buffer) {
  let offset = 8, width = 0, height = 0, colorType = 0;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('ascii', offset + 4, offset + 8);
    const data = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0); height = data.readUInt32BE(4);
      if (data[8] !== 8 || data[12] !== 0) throw new Error('PNG: only 8-bit, non-interlaced');
      colorType = data[9];
    } else if (type === 'IDAT') idat.push(data);
    offset += 12 + length;
  }
  const channels = colorType === 6 ? 4 : colorType === 2 ? 3 : 0;
  if (!channels) throw new Error(`PNG colour type ${colorType}`);
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = Buffer.alloc(width * height * 3);
  let previous = Buffer.alloc(stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const line = Buffer.from(raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1)));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? line[i - channels] : 0, b = previous[i], c = i >= channels ? previous[i - channels] : 0;
      let add = 0;
      if (filter === 1) add = a;
      else if (filter === 2) add = b;
      else if (filter === 3) add = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        add = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      line[i] = (line[i] + add) & 255;
    }
    for (let x = 0; x < width; ++x)
      for (let k = 0; k < 3; ++k) pixels[(y * width + x) * 3 + k] = line[x * channels + k];
    previous = line;
  }
  return { width, height, pixels };
}

// The model's silhouette: pixels unlike the page's background (the colour of the bottom-right
// corner), outside the panel.
function silhouette(image, panel) {
  const { width, height, pixels } = image;
  const corner = ((height - 1) * width + width - 1) * 3;
  const bg = [pixels[corner], pixels[corner + 1], pixels[corner + 2]];
  const mask = new Uint8Array(width * height);
  let count = 0, x0 = width, y0 = height, x1 = -1, y1 = -1;
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) {
      if (x >= panel.left - 2 && x <= panel.right + 2 && y >= panel.top - 2 && y <= panel.bottom + 2) continue;
      const i = (y * width + x) * 3;
      const d = Math.max(Math.abs(pixels[i] - bg[0]), Math.abs(pixels[i + 1] - bg[1]), Math.abs(pixels[i + 2] - bg[2]));
      if (d > 12) {
        mask[y * width + x] = 1;
        ++count;
        x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
      }
    }
  const free = width * height - (panel.right - panel.left + 5) * (panel.bottom - panel.top + 5);
  return { mask, count, share: count / free, box: [x0, y0, x1, y1] };
}

function meanDifference(a, b, maskA, maskB) {
  let sum = 0, n = 0;
  for (let p = 0; p < maskA.length; ++p) {
    if (!maskA[p] && !maskB[p]) continue;
    for (let k = 0; k < 3; ++k) sum += Math.abs(a.pixels[p * 3 + k] - b.pixels[p * 3 + k]);
    n += 3;
  }
  return n ? sum / n : 0;
}

// --- the run ---
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'ellicast-view-'));
// LIVE_VIEW_RATE (bits/s) and LIVE_VIEW_LOSS let the benchmark (bench/run.sh live) play the bunny at 1 Mbit/s.
const rate = process.env.LIVE_VIEW_RATE || '150000', loss = process.env.LIVE_VIEW_LOSS || '0.3';
const viewer = spawn(ellicast, ['view', stream, '--port', '0', '--loss', loss, '--seed', '3', '--rate', rate,
  '--reference', reference, '--wait-for-viewer', '60', '--linger', '60', '-q'], { stdio: ['ignore', 'ignore', 'pipe'], detached: true });
children.push(viewer);
let viewerLog = '';
viewer.stderr.on('data', (d) => { viewerLog += d.toString(); });
const url = (await waitForLine(viewer, /view: (http:\/\/\S+)/, 'ellicast view'))[1];
console.log(`page: ${url}`);

const browser = spawn(chromiumPath, ['--headless', '--no-sandbox', '--no-first-run', '--disable-gpu-sandbox', '--disable-dev-shm-usage',
  '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--remote-debugging-port=0', `--user-data-dir=${scratch}`,
  '--window-size=900,700', 'about:blank'], { stdio: ['ignore', 'ignore', 'pipe'], detached: true });
children.push(browser);
const devtools = (await waitForLine(browser, /DevTools listening on (ws:\/\/\S+)/, 'chromium'))[1];
const debugPort = new URL(devtools).port;
let targets = [];
for (let i = 0; i < 50 && !targets.some((t) => t.type === 'page'); ++i) {
  targets = await (await fetch(`http://127.0.0.1:${debugPort}/json/list`)).json();
  if (!targets.some((t) => t.type === 'page')) await sleep(100);
}
const pageTarget = targets.find((t) => t.type === 'page');
const socket = new WebSocket(pageTarget.webSocketDebuggerUrl, { perMessageDeflate: false, maxPayload: 256 << 20 });
await new Promise((resolve, reject) => { socket.once('open', resolve); socket.once('error', reject); });
let nextId = 1;
const pending = new Map();
const consoleErrors = [];
socket.on('message', (raw) => {
  const message = JSON.parse(raw.toString());
  if (message.id && pending.has(message.id)) {
    const { resolve, reject } = pending.get(message.id);
    pending.delete(message.id);
    if (message.error) reject(new Error(JSON.stringify(message.error))); else resolve(message.result);
  } else if (message.method === 'Runtime.exceptionThrown') {
    consoleErrors.push(message.params.exceptionDetails.exception?.description || message.params.exceptionDetails.text);
  } else if (message.method === 'Runtime.consoleAPICalled' && message.params.type === 'error') {
    consoleErrors.push(message.params.args.map((a) => a.value ?? a.description).join(' '));
  }
});
const send = (method, params = {}) => new Promise((resolve, reject) => {
  const id = nextId++;
  pending.set(id, { resolve, reject });
  socket.send(JSON.stringify({ id, method, params }));
});
const evaluate = async (expression) => {
  const r = await send('Runtime.evaluate', { expression, returnByValue: true });
  return r.result.value;
};
await send('Page.enable');
await send('Runtime.enable');
await send('Page.navigate', { url });

const state = () => evaluate(`(() => { const v = window.ellicastView; if (!v) return null;
  const s = v.status; const p = document.getElementById('panel').getBoundingClientRect();
  return { shown: v.shownVersion, latest: v.modelVersion, triangles: v.triangles, fps: v.fps, problem: v.problem,
           loadErrors: v.loadErrors, status: s, panel: { left: p.left, top: p.top, right: p.right, bottom: p.bottom },
           text: { points: document.getElementById('points').textContent, exact: document.getElementById('exact').textContent,
                   packets: document.getElementById('packets').textContent, error: document.getElementById('error').textContent,
                   connection: document.getElementById('connection').textContent } }; })()`);

async function screenshot(name) {
  await sleep(300);  // let a model that has just loaded be drawn
  const s = await state();
  const shot = await send('Page.captureScreenshot', { format: 'png' });
  const file = path.join(outdir, name);
  fs.writeFileSync(file, Buffer.from(shot.data, 'base64'));
  return { state: s, file, image: decodePng(Buffer.from(shot.data, 'base64')) };
}

const moments = [];
const started = Date.now();
let half = null, first = null, last = null;
while (Date.now() - started < 200000) {
  const s = await state();
  if (s && s.problem) break;
  if (s && s.status) {
    const ins = s.status.points.inserted, declared = s.status.points.declared;
    if (!first && s.shown >= 1) { first = await screenshot('live-view-1-first.png'); moments.push(['first picture', first]); }
    else if (first && !half && s.shown === s.latest && s.shown > first.state.shown && ins > first.state.status.points.inserted &&
             s.status.exact_objects === 0) {
      half = await screenshot('live-view-2-refined.png'); moments.push(['refined', half]);
    }
    if (s.status.final && s.shown === s.latest && s.status.exact_objects === s.status.objects.length) {
      last = await screenshot('live-view-3-exact.png'); moments.push(['exact', last]);
      break;
    }
  }
  await sleep(100);
}
const serverStatus = await (await fetch(new URL('/status.json', url))).json();
const orbitFps = await send('Runtime.evaluate', { expression: 'window.ellicastView.measureOrbit(3000)', awaitPromise: true,
                                                   returnByValue: true }).then((r) => r.result.value).catch(() => null);
const timing = await evaluate(`(() => { const v = window.ellicastView;
  return { latencies: v.latencies, published: v.published, fps: v.fps, stages: v.stages,
           heap: performance.memory ? performance.memory.usedJSHeapSize : null, software: v.software }; })()`);

for (const [name, m] of moments) {
  const st = m.state.status;
  console.log(`${name}: ${m.file}: ${st.seconds.toFixed(2)} s after tune-in, model #${m.state.shown}, ` +
              `${m.state.triangles} triangles, ${st.points.inserted}/${st.points.declared} points shown, ` +
              `error ${st.error.rms_percent === null ? '-' : st.error.rms_percent.toFixed(3) + '%'}, ${m.state.fps.toFixed(0)} frames drawn/s`);
}
if (timing && timing.latencies.length) {
  const sorted = [...timing.latencies].sort((a, b) => a - b);
  const median = sorted[Math.floor(sorted.length / 2)], worst = sorted[sorted.length - 1];
  console.log(`figures: first picture published ${timing.published[0].toFixed(2)} s after tune-in and drawn ` +
              `${timing.latencies[0].toFixed(0)} ms after its event (${(timing.published[0] + timing.latencies[0] / 1000).toFixed(2)} s); ` +
              `${timing.latencies.length} pictures drawn, ` +
              `event to first frame median ${median.toFixed(0)} ms, worst ${worst.toFixed(0)} ms; ` +
              `orbiting the exact model: ${orbitFps === null ? '?' : orbitFps.toFixed(0)} frames/s` +
              `${timing.software ? ' (software renderer)' : ''}; JS heap ` +
              `${timing.heap ? (timing.heap / 1048576).toFixed(1) + ' MB' : 'unknown'}`);
}
if (timing && timing.stages.length) {
  const med = (k) => { const a = timing.stages.map((x) => x[k]).sort((x, y) => x - y); return a[Math.floor(a.length / 2)]; };
  console.log(`figures: a model's event to its first frame, median of each step: waiting ${med('wait').toFixed(0)} ms, ` +
              `fetching ${med('fetch').toFixed(0)} ms (${(med('bytes') / 1048576).toFixed(1)} MB), parsing ` +
              `${med('parse').toFixed(0)} ms, drawing ${med('draw').toFixed(0)} ms`);
}
if (process.env.LIVE_VIEW_FIGURES_ONLY) {  // bench/run.sh live: the figures, not the test's checks
  clearTimeout(deadline);
  cleanup();
  process.exit(0);
}
check(consoleErrors.length === 0, `no script error in the page${consoleErrors.length ? ': ' + consoleErrors.slice(0, 3).join(' | ') : ''}`);
check(first && half && last, 'the page showed a first picture, then a refined one (more points), then the exact model');
if (first && half && last) {
  const shapes = [first, half, last].map((m) => silhouette(m.image, m.state.panel));
  shapes.forEach((s, i) => {
    const [x0, y0, x1, y1] = s.box;
    const cx = (x0 + x1) / 2 / first.image.width, cy = (y0 + y1) / 2 / first.image.height;
    check(s.share > 0.03 && s.share < 0.8,
          `screenshot ${i + 1}: the model covers ${(100 * s.share).toFixed(1)}% of the view (3-80% expected)`);
    check(cx > 0.2 && cx < 0.8 && cy > 0.2 && cy < 0.8,
          `screenshot ${i + 1}: the silhouette is centred (centre at ${(100 * cx).toFixed(0)}%, ${(100 * cy).toFixed(0)}% of the view)`);
  });
  let both = 0, either = 0;
  for (let p = 0; p < shapes[0].mask.length; ++p) { both += shapes[0].mask[p] & shapes[2].mask[p]; either += shapes[0].mask[p] | shapes[2].mask[p]; }
  const iou = either ? both / either : 0;
  check(iou > 0.7, `the first picture's silhouette is the exact model's (overlap ${(100 * iou).toFixed(0)}%, over 70% expected)`);
  const change = meanDifference(first.image, last.image, shapes[0].mask, shapes[2].mask);
  check(change > 2, `the picture changed as detail arrived (mean difference ${change.toFixed(1)} levels between the first and the exact picture)`);
  const e1 = first.state.status.error.rms_percent, e3 = last.state.status.error.rms_percent;
  check(e3 !== null && e3 < 0.05, `the exact model's surface error is ${e3}% of the diagonal (under 0.05% expected)`);
  check(e1 === null || e3 < e1, `the error fell from the first picture (${e1}%) to the exact model (${e3}%)`);
  const st = last.state.status;
  check(st.points.received === st.points.declared &&
        (st.points.inserted === st.points.declared || st.exact_objects === st.objects.length),
        `every point arrived (${st.points.received} of ${st.points.declared}) and shows, inserted ` +
        `(${st.points.inserted}) or in the exact mesh`);
  check(st.points.received === serverStatus.points.received && st.packets.accepted === serverStatus.packets.accepted &&
        st.model.version === serverStatus.model.version,
        `the panel's counts are the server's (points ${st.points.received}/${serverStatus.points.received}, packets ` +
        `${st.packets.accepted}/${serverStatus.packets.accepted}, model #${st.model.version}/#${serverStatus.model.version})`);
  const expectedPoints = `${st.points.declared.toLocaleString('en')} of ${st.points.declared.toLocaleString('en')}`;
  check(last.state.text.points.startsWith(expectedPoints), `the panel says "${last.state.text.points}" points held`);
  check(last.state.text.exact === `${st.objects.length} of ${st.objects.length}`, `the panel says "${last.state.text.exact}" exact objects`);
  check(last.state.text.connection === 'complete', `the panel says the reception is "${last.state.text.connection}"`);
  check(serverStatus.packets.lost > 0, `the channel lost packets (${serverStatus.packets.lost} of ${serverStatus.packets.sent})`);
  check(first.state.status.seconds < last.state.status.seconds,
        `the first picture (${first.state.status.seconds.toFixed(2)} s) came before the exact model (${last.state.status.seconds.toFixed(2)} s)`);
}
socket.close();
clearTimeout(deadline);
cleanup();
if (failures.length) {
  console.log(`ellicast view's log:\n${viewerLog.slice(-3000)}`);
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
console.log('every check passed');
process.exit(0);
