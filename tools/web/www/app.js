// The page: the scene editor, the pickers, the player's clock and the display. Frames
// are drawn by the worker (worker.js); this thread only shows them.

import init, * as kernel from './pkg/embedded_raytracer_web.js';

/// The loader's limit on a scene file (`scene_file::MAX_FILE_SIZE`, 1 MiB): a text
/// from a share link is refused past it before it is inflated further.
const MAX_TEXT = 1 << 20;
/// The longest share-link fragment read: a deflated 1 MiB text fits several times over.
const MAX_FRAGMENT = 4 << 20;
/// Orbit step of an arrow key (the preview's 5°).
const ORBIT_STEP = (5 * Math.PI) / 180;
/// Quiet time after a keystroke before the text is drawn.
const EDIT_DELAY_MS = 150;

/// The panels the boards and the usual breakouts have.
const PANELS = [
  ['file', "scene file's size"],
  ['240x240', '240×240 ST7789'],
  ['320x240', '320×240 ILI9341'],
  ['128x64', '128×64 SSD1306'],
];

/// Each board example's panel, colour format and method (`boards/*/src/frame.rs`), and
/// the scene it draws.
const BOARDS = [
  { name: 'Pico (RP2040) + ST7789', panel: '240x240', display: 'rgb565', integer: true, scene: 'circling' },
  { name: 'Pico (RP2040) + SSD1306', panel: '128x64', display: 'binary-dither', integer: true, scene: 'circling' },
  { name: 'ESP32-C3 + ST7789', panel: '240x240', display: 'rgb565', integer: true, scene: 'circling' },
  { name: 'Pico 2 (RP2350) + ST7789', panel: '240x240', display: 'rgb565', integer: false, scene: 'bounce' },
  { name: 'STM32F407 + ST7789', panel: '240x240', display: 'rgb565', integer: false, scene: 'bounce' },
];

const $ = (id) => document.getElementById(id);

// The module is compiled once; the menus read its tables here and every worker
// instantiates the same compiled module.
const wasmUrl = new URL('./pkg/embedded_raytracer_web_bg.wasm', import.meta.url);
const module = await WebAssembly.compile(await (await fetch(wasmUrl)).arrayBuffer());
await init({ module_or_path: module });

const [stepping, sphereTest, sqrt] = kernel.defaultMethod().split('/');

/// What the pickers chose; `viewSpec` sends it to the worker.
const view = {
  display: 'rgb888', bayer: '8', theme: 'oled-blue',
  stepping, sphereTest, sqrt, integer: false,
  sampling: 'center', secondary: 'convex', size: 'file',
  azimuth: 0, elevation: 0, zoom: 0, diff: false,
};

const state = {
  text: '',
  /// The last text that loaded, its name in the menu and its size and timing.
  goodText: null,
  info: null,
  elevation: [-1.5, 1.5],
  frame: 0,
  playing: true,
  /// When frame 0 of the loop was due, while playing.
  start: performance.now(),
  /// When recent frames were shown, for the achieved rate.
  shown: [],
  scale: 'auto',
  error: null,
  lastReport: null,
  /// The last frame's marks: per pixel 1 traced, 2 sent (`Player::marks`).
  marks: null,
  /// Frames abandoned for an edit.
  cancelled: 0,
};

// ---------------------------------------------------------------- the worker

let worker;
/// The id of the frame asked for and not yet drawn (false: none).
let busy = false;
/// Something changed while a frame was drawn: ask again when it is.
let pending = false;
/// The text the worker holds (null: a fresh worker holds none).
let sentText = null;
let nextId = 1;
let editTimer = null;
const waiters = [];

function startWorker() {
  worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = (event) => onReply(event.data);
  worker.postMessage({ module });
  sentText = null;
  busy = false;
}

/// Abandons the frame being drawn: the worker is ended and a fresh one started.
function cancel() {
  worker.terminate();
  startWorker();
}

function viewSpec() {
  const v = view;
  const method = `${v.integer ? 'integer/' : ''}${v.stepping}/${v.sphereTest}/${v.sqrt}`;
  const pairs = {
    display: v.display, bayer: v.bayer, theme: v.theme, method, sampling: v.sampling,
    secondary: v.secondary, size: v.size, azimuth: v.azimuth, elevation: v.elevation,
    zoom: v.zoom, diff: v.diff ? 1 : 0,
  };
  return Object.entries(pairs).map(([k, x]) => `${k}=${x}`).join('&');
}

/// Asks the worker for the frame shown; while it draws one, the newest request waits.
function request() {
  if (busy) {
    pending = true;
    return;
  }
  pending = false;
  const message = { id: nextId++, view: viewSpec(), frame: state.frame };
  // A fresh worker gets the last good scene first, so a text it refuses keeps that
  // scene (and its picture) playing.
  if (sentText === null && state.goodText !== null && state.text !== state.goodText) {
    worker.postMessage({ ...message, text: state.goodText });
    sentText = state.goodText;
    message.id = nextId++;
  }
  if (state.text !== sentText) {
    message.text = state.text;
    sentText = state.text;
  }
  worker.postMessage(message);
  busy = message.id;
}

function onReply(reply) {
  if (reply.id !== busy) {
    // A fresh worker's reload of the last good scene: not painted, the picture on
    // screen is that scene's already.
    if (reply.info) takeInfo(reply.info, state.goodText);
    return;
  }
  busy = false;
  if (reply.error) {
    showError(reply.error);
  } else {
    if (reply.info) {
      takeInfo(reply.info, sentText);
      showError(null);
    }
    if (reply.failed) {
      showFailure(reply.failed);
      if (reply.failed.includes('RuntimeError')) cancel();
    } else {
      paint(reply);
    }
  }
  if (pending) request();
  settle();
}

function takeInfo(info, text) {
  const moved = !state.info || state.info.frames !== info.frames || state.info.fps !== info.fps;
  state.info = info;
  state.goodText = text;
  state.elevation = info.elevation;
  if (moved) {
    state.frame %= Math.max(1, info.frames);
    if (state.playing) play(true);
  }
  updateTransport();
}

function idle() {
  return !busy && !pending && editTimer === null;
}

/// Resolves every waiter of `whenIdle` once nothing is asked or drawn.
function settle() {
  if (idle()) for (const resolve of waiters.splice(0)) resolve();
}

function whenIdle() {
  return new Promise((resolve) => {
    waiters.push(resolve);
    settle();
  });
}

// ---------------------------------------------------------------- the display

const canvas = $('display');
const overlay = $('overlay');
const ctx = canvas.getContext('2d');
const octx = overlay.getContext('2d');

function scale() {
  if (state.scale !== 'auto') return Number(state.scale);
  // The preview's default: a window about 640 pixels wide.
  return Math.min(8, Math.max(1, Math.floor(640 / canvas.width)));
}

function applyScale() {
  const s = scale();
  for (const c of [canvas, overlay]) {
    c.style.width = `${c.width * s}px`;
    c.style.height = `${c.height * s}px`;
  }
}

function paint({ report, rgba, marks, ms, differing }) {
  const { width, height } = report;
  if (canvas.width !== width || canvas.height !== height) {
    for (const c of [canvas, overlay]) {
      c.width = width;
      c.height = height;
    }
    applyScale();
  }
  ctx.putImageData(new ImageData(new Uint8ClampedArray(rgba.buffer, rgba.byteOffset, rgba.length), width, height), 0, 0);
  state.marks = marks;
  paintMarks();
  state.lastReport = { ...report, ms, differing };
  const now = performance.now();
  state.shown.push(now);
  while (state.shown.length && now - state.shown[0] > 1000) state.shown.shift();
  showStatus();
}

/// The overlay of a frame of a scene that moves: pixels traced but not sent in
/// translucent yellow, pixels sent in translucent red.
function paintMarks() {
  const marks = state.marks ?? [];
  const image = octx.createImageData(overlay.width, overlay.height);
  if ($('marks').checked && state.info?.moves) {
    const d = image.data;
    for (let k = 0; k < marks.length; k++) {
      if (marks[k] & 2) d.set([255, 40, 40, 140], 4 * k);
      else if (marks[k] & 1) d.set([255, 220, 0, 90], 4 * k);
    }
  }
  octx.putImageData(image, 0, 0);
}

function percent(n, r) {
  return `${((100 * n) / Math.max(1, r.width * r.height)).toFixed(1)}%`;
}

function showStatus() {
  const r = state.lastReport;
  if (!r) return;
  const info = state.info;
  let first;
  if (view.diff) {
    first = `D: ${r.differing} px differ from ${kernel.referenceMethod()} (convex)`;
  } else if (info?.moves) {
    const played = state.playing ? `${rate()} fps` : 'paused';
    first = `frame ${r.frame + 1}/${info.frames} ${played} · traced ${r.traced} px (${percent(r.traced, r)}) · ` +
      `sent ${r.sent} px (${percent(r.sent, r)}) in ${r.windows} windows${r.full ? ' · whole frame' : ''}`;
  } else {
    const deg = (x) => Math.round((x * 180) / Math.PI);
    first = `still · az ${deg(view.azimuth)}° el ${deg(view.elevation)}° zoom ${-view.zoom}`;
  }
  let model = view.display;
  if (model.includes('dither')) model += ` ${view.bayer}×${view.bayer}`;
  let method = `${view.integer ? 'integer/' : ''}${view.stepping}/${view.sphereTest}/${view.sqrt}`;
  if (view.integer && r.arithmetic !== 'integer') method += ' → f32 (the integer kernel\'s rule does not take this frame)';
  const secondary = info?.features ? ` · ${view.secondary}` : '';
  $('status-frame').textContent = first;
  $('status-method').textContent = `${r.width}×${r.height} ${model} · ${method} · ${view.sampling}${secondary}` +
    (r.refused ? ` · refused: ${r.refused}` : '');
  $('status-time').textContent = `${r.ms.toFixed(2)} ms a frame in this browser on this machine, not on a board`;
}

function rate() {
  const s = state.shown;
  if (s.length < 2 || s[s.length - 1] === s[0]) return '-';
  return ((s.length - 1) / ((s[s.length - 1] - s[0]) / 1000)).toFixed(0);
}

// ---------------------------------------------------------------- the editor

const textArea = $('text');
const gutter = $('gutter');

function setText(text) {
  textArea.value = text;
  state.text = text;
  renderGutter();
}

/// The gutter's line numbers; the error's line (or, without one, the table its field
/// path names) marked.
function renderGutter() {
  const lines = textArea.value.split('\n').length;
  const bad = state.error?.line ?? locate(state.error?.field);
  const out = [];
  for (let k = 1; k <= lines; k++) out.push(k === bad ? `<span class="bad">${k}</span>` : String(k));
  gutter.innerHTML = out.join('\n');
  gutter.scrollTop = textArea.scrollTop;
}

/// The line of the table a field path names (`sphere[2].radius`: the third
/// `[[sphere]]`; `camera.width`: `[camera]`), for errors the parser gives no line for.
function locate(field) {
  const m = field?.match(/^([a-z_]+)(?:\[(\d+)\])?/);
  if (!m) return undefined;
  const [, table, index] = m;
  const header = index === undefined ? `[${table}]` : `[[${table}]]`;
  let seen = 0;
  const lines = textArea.value.split('\n');
  for (let k = 0; k < lines.length; k++) {
    if (lines[k].trim().startsWith(header) && seen++ === Number(index ?? 0)) return k + 1;
  }
  return undefined;
}

function showError(error) {
  state.error = error;
  const box = $('error');
  if (error) {
    const at = error.line ? `line ${error.line}: ` : '';
    const field = error.field ? `${error.field}: ` : '';
    box.textContent = `${at}${field}${error.reason}\n(the picture is the last scene that loaded)`;
  }
  box.hidden = !error;
  renderGutter();
}

function showFailure(message) {
  const box = $('error');
  box.textContent = `${message}\n(the picture is the last frame drawn)`;
  box.hidden = false;
}

textArea.addEventListener('input', () => {
  state.text = textArea.value;
  $('scene').value = '';
  renderGutter();
  clearTimeout(editTimer);
  editTimer = setTimeout(textChanged, EDIT_DELAY_MS);
});

/// Draws the edited text; the frame being drawn is of the old text: it is abandoned.
function textChanged() {
  clearTimeout(editTimer);
  editTimer = null;
  if (busy) {
    cancel();
    state.cancelled++;
  }
  request();
}
textArea.addEventListener('scroll', () => { gutter.scrollTop = textArea.scrollTop; });

// ---------------------------------------------------------------- the clock

function moves() {
  return Boolean(state.info?.moves);
}

/// While playing, the frame due now (frame k at k / fps seconds, looping); frames are
/// skipped when drawing is slower than the frame rate.
function tick() {
  requestAnimationFrame(tick);
  if (!state.playing || !moves() || busy) return;
  const { fps, frames } = state.info;
  const due = Math.floor(((performance.now() - state.start) / 1000) * fps) % frames;
  if (due !== state.frame) {
    state.frame = due;
    request();
  }
}

function play(on) {
  state.playing = on;
  if (on && moves()) {
    // Resume from the frame shown: halfway through it.
    state.start = performance.now() - ((state.frame + 0.5) / state.info.fps) * 1000;
  }
  state.shown = [];
  updateTransport();
  showStatus();
}

function step(delta) {
  if (!moves()) return;
  play(false);
  const n = state.info.frames;
  state.frame = (((state.frame + delta) % n) + n) % n;
  request();
}

function updateTransport() {
  $('play').textContent = state.playing && moves() ? 'Pause' : 'Play';
  for (const id of ['play', 'back', 'forward']) $(id).disabled = !moves();
}

// ---------------------------------------------------------------- the pickers

function fill(select, items) {
  select.replaceChildren(...items.map(([value, label]) => new Option(label ?? value, value)));
}

fill($('scene'), [['', '(edited)'], ...kernel.sceneNames().map((n) => [n, `${n}.toml`])]);
fill($('panel'), PANELS);
fill($('model'), kernel.displayModels().map((m) => [m]));
fill($('stepping'), kernel.methodAxis('stepping').map((m) => [m]));
fill($('sphere-test'), kernel.methodAxis('sphere-test').map((m) => [m]));
fill($('sqrt'), kernel.methodAxis('sqrt').map((m) => [m]));
fill($('sampling'), kernel.samplings().map((m) => [m]));
fill($('secondary'), kernel.secondaries().map((m) => [m]));
fill($('board'), [['', '—'], ...BOARDS.map((b, k) => [String(k), `${b.name} (${b.display}, ${b.integer ? 'integer' : 'f32'}; draws ${b.scene})`])]);
fill($('scale'), [['auto', 'auto'], ...[1, 2, 3, 4, 5, 6, 8].map((s) => [String(s), `${s}×`])]);

/// The pickers bound to a `view` key.
const PICKERS = {
  panel: 'size', model: 'display', bayer: 'bayer', theme: 'theme', stepping: 'stepping',
  'sphere-test': 'sphereTest', sqrt: 'sqrt', sampling: 'sampling', secondary: 'secondary',
};

function syncPickers() {
  for (const [id, key] of Object.entries(PICKERS)) {
    const select = $(id);
    if (![...select.options].some((o) => o.value === String(view[key]))) {
      select.add(new Option(String(view[key]).replace('x', '×')));
    }
    select.value = String(view[key]);
  }
  $('integer').checked = view.integer;
  $('diff').checked = view.diff;
  $('bayer').disabled = !view.display.includes('dither');
  $('theme').disabled = !view.display.startsWith('binary');
}

function changed() {
  syncPickers();
  request();
}

for (const [id, key] of Object.entries(PICKERS)) {
  $(id).addEventListener('change', (e) => {
    view[key] = e.target.value;
    $('board').value = '';
    changed();
  });
}
$('integer').addEventListener('change', (e) => { view.integer = e.target.checked; $('board').value = ''; changed(); });
$('diff').addEventListener('change', (e) => { view.diff = e.target.checked; changed(); });
$('marks').addEventListener('change', paintMarks);
$('scale').addEventListener('change', (e) => { state.scale = e.target.value; applyScale(); });

$('board').addEventListener('change', (e) => {
  const board = BOARDS[Number(e.target.value)];
  if (!board) return;
  Object.assign(view, {
    size: board.panel, display: board.display, integer: board.integer, bayer: '8',
    stepping, sphereTest, sqrt, sampling: 'center', secondary: 'convex',
  });
  changed();
});

$('scene').addEventListener('change', (e) => {
  if (!e.target.value) return;
  loadScene(kernel.sceneText(e.target.value));
});

function loadScene(text) {
  setText(text);
  Object.assign(view, { azimuth: 0, elevation: 0, zoom: 0 });
  state.frame = 0;
  state.info = null;
  if (busy) cancel();
  play(true);
  request();
}

// ---------------------------------------------------------------- orbit and keys

function orbit(dAzimuth, dElevation) {
  view.azimuth += dAzimuth;
  const [lo, hi] = state.elevation;
  view.elevation = Math.min(hi, Math.max(lo, view.elevation + dElevation));
  request();
}

function zoom(steps) {
  view.zoom = Math.min(40, Math.max(-40, view.zoom + steps));
  request();
}

function resetView() {
  Object.assign(view, { azimuth: 0, elevation: 0, zoom: 0 });
  request();
}

const stage = $('stage');
let drag = null;
stage.addEventListener('pointerdown', (e) => {
  drag = { x: e.clientX, y: e.clientY };
  stage.setPointerCapture(e.pointerId);
});
stage.addEventListener('pointerup', () => { drag = null; });
stage.addEventListener('pointermove', (e) => {
  if (!drag) return;
  // Half a turn per display width, both axes (the preview's drag).
  const perPx = Math.PI / (canvas.width * scale());
  orbit(-(e.clientX - drag.x) * perPx, (e.clientY - drag.y) * perPx);
  drag = { x: e.clientX, y: e.clientY };
});
stage.addEventListener('wheel', (e) => {
  e.preventDefault();
  zoom(e.deltaY > 0 ? 1 : -1);
}, { passive: false });

document.addEventListener('keydown', (e) => {
  if (e.target === textArea || e.target.tagName === 'SELECT' || e.ctrlKey || e.metaKey || e.altKey) return;
  // A focused button takes Space and Enter itself.
  if (e.target.tagName === 'BUTTON' && (e.key === ' ' || e.key === 'Enter')) return;
  const keys = {
    ArrowLeft: () => orbit(-ORBIT_STEP, 0),
    ArrowRight: () => orbit(ORBIT_STEP, 0),
    ArrowUp: () => orbit(0, ORBIT_STEP),
    ArrowDown: () => orbit(0, -ORBIT_STEP),
    '+': () => zoom(-1),
    '=': () => zoom(-1),
    '-': () => zoom(1),
    r: resetView,
    d: () => { view.diff = !view.diff; changed(); },
    ' ': () => play(!state.playing),
    '.': () => step(1),
    ',': () => step(-1),
  };
  const model = kernel.displayModels()[Number(e.key) - 1];
  const action = keys[e.key.length === 1 ? e.key.toLowerCase() : e.key] ??
    (model && (() => { view.display = model; changed(); }));
  if (action) {
    e.preventDefault();
    action();
  }
});

$('play').addEventListener('click', () => play(!state.playing));
$('back').addEventListener('click', () => step(-1));
$('forward').addEventListener('click', () => step(1));
$('reset').addEventListener('click', resetView);

// ---------------------------------------------------------------- share and export

function base64url(bytes) {
  let s = '';
  for (const b of bytes) s += String.fromCharCode(b);
  return btoa(s).replaceAll('+', '-').replaceAll('/', '_').replace(/=+$/, '');
}

function unbase64url(text) {
  const s = atob(text.replaceAll('-', '+').replaceAll('_', '/'));
  return Uint8Array.from(s, (c) => c.charCodeAt(0));
}

async function deflate(text) {
  const stream = new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/// Inflates a share link's scene, refusing it as soon as it passes `MAX_TEXT` bytes.
async function inflate(bytes) {
  const reader = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const chunks = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > MAX_TEXT) {
      await reader.cancel();
      throw new Error(`the shared scene is more than ${MAX_TEXT} bytes`);
    }
    chunks.push(value);
  }
  const all = new Uint8Array(total);
  let at = 0;
  for (const c of chunks) {
    all.set(c, at);
    at += c.length;
  }
  return new TextDecoder('utf-8', { fatal: true }).decode(all);
}

async function shareLink() {
  const hash = `#scene=${base64url(await deflate(state.text))}&view=${encodeURIComponent(viewSpec())}`;
  history.replaceState(null, '', hash);
  const note = $('share-note');
  note.textContent = location.href;
  note.hidden = false;
  try {
    await navigator.clipboard.writeText(location.href);
    note.textContent = `copied: ${location.href}`;
  } catch {
    // No clipboard (an insecure origin, or no permission): the link is shown.
  }
  return location.href;
}

/// The scene and view of a share link, or null without one.
async function readLink() {
  const params = new URLSearchParams(location.hash.slice(1));
  const scene = params.get('scene');
  if (scene === null) return null;
  if (scene.length > MAX_FRAGMENT) throw new Error('the shared scene is too long');
  const text = await inflate(unbase64url(scene));
  return { text, view: params.get('view') ?? '' };
}

/// A view spec's pairs onto `view` (the keys it knows).
function applySpec(spec) {
  for (const [k, x] of new URLSearchParams(spec)) {
    if (k === 'method') {
      const parts = x.split('/');
      view.integer = parts[0] === 'integer';
      if (view.integer) parts.shift();
      [view.stepping, view.sphereTest, view.sqrt] = parts;
    } else if (k === 'diff') {
      view.diff = x === '1';
    } else if (['azimuth', 'elevation', 'zoom'].includes(k)) {
      view[k] = Number(x) || 0;
    } else if (k in view) {
      view[k] = x;
    }
  }
}

function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function baseName() {
  return $('scene').value || 'scene';
}

/// The display as a PNG, each display pixel `s` × `s` image pixels (the preview's
/// `--scale`), without smoothing.
function png(s = scale()) {
  const out = document.createElement('canvas');
  out.width = canvas.width * s;
  out.height = canvas.height * s;
  const c = out.getContext('2d');
  c.imageSmoothingEnabled = false;
  c.drawImage(canvas, 0, 0, out.width, out.height);
  return new Promise((resolve) => out.toBlob(resolve, 'image/png'));
}

$('export-png').addEventListener('click', async () => {
  download(await png(), `${baseName()}-${canvas.width}x${canvas.height}-${view.display}.png`);
});
$('export-toml').addEventListener('click', () => {
  download(new Blob([state.text], { type: 'application/toml' }), `${baseName()}.toml`);
});
$('share').addEventListener('click', shareLink);

// ---------------------------------------------------------------- start

startWorker();
let link = null;
try {
  link = await readLink();
} catch (e) {
  const note = $('share-note');
  note.textContent = `share link: ${e.message} (the standard lab scene instead)`;
  note.hidden = false;
}
if (link) {
  applySpec(link.view);
  setText(link.text);
} else {
  $('scene').value = 'lab';
  setText(kernel.sceneText('lab'));
}
syncPickers();
updateTransport();
request();
requestAnimationFrame(tick);

// For the browser test (tools/web/test): wait for the display, go to a frame, the
// PNG export's bytes. Set once the first frame is asked for, so that waiting for the
// display never returns before it.
window.ertrace = {
  whenIdle,
  /// An edit drawn now, not after the quiet time.
  textChanged,
  show(frame) {
    play(false);
    state.frame = frame;
    request();
  },
  async png(s) {
    return new Uint8Array(await (await png(s)).arrayBuffer());
  },
  shareLink,
  state,
  view,
};
