// The page in a real browser: Debian's chromium, headless, driven by puppeteer-core,
// against the built folder (`bash tools/web/build.sh`) served on 127.0.0.1. Run by
// `.ci/web`; by hand: `cd tools/web/test && npm ci && node --test web.test.mjs`.
//
// Environment: WEB_DIR (the built folder, default target/web), CHROMIUM (default
// /usr/bin/chromium), WEB_UPDATE=1 (write docs/web.png, the page's screenshot).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import puppeteer from 'puppeteer-core';

const ROOT = fileURLToPath(new URL('../../..', import.meta.url)).replace(/\/$/, '');
const SITE_DIR = resolve(process.env.WEB_DIR ?? join(ROOT, 'target/web'));
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
const UPDATE = process.env.WEB_UPDATE === '1';
/// A step that waits for the page: generous, the machine may be loaded.
const WAIT_MS = 120_000;

const TYPES = {
  '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css',
  '.wasm': 'application/wasm', '.png': 'image/png',
};

let server;
let site;
let browser;
let scratch;

/// The folder's files, nothing outside it, on a port of 127.0.0.1.
function serve(dir) {
  const s = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const file = normalize(join(dir, path.endsWith('/') ? `${path}index.html` : path));
    if (!file.startsWith(dir + sep) || !existsSync(file)) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream' });
    res.end(readFileSync(file));
  });
  return new Promise((ok) => s.listen(0, '127.0.0.1', () => ok(s)));
}

/// The render CLI, as a person runs it from the repository's root.
function cli(...args) {
  execFileSync('cargo', ['run', '--release', '--quiet', '-p', 'embedded-raytracer-cli', '--', ...args], {
    cwd: ROOT,
    // Its progress lines are not the test's; its errors come with the exception.
    stdio: ['ignore', 'ignore', 'pipe'],
  });
}

before(async () => {
  assert.ok(existsSync(join(SITE_DIR, 'index.html')), `${SITE_DIR}: build it with tools/web/build.sh`);
  scratch = mkdtempSync(join(tmpdir(), 'ertrace-web-'));
  cli('scenes/lab.toml', '--output', join(scratch, 'lab.png'));
  cli('scenes/bounce.toml', '--frames', '30', '--output-frames', join(scratch, 'bounce'));
  server = await serve(SITE_DIR);
  site = `http://127.0.0.1:${server.address().port}/`;
  browser = await puppeteer.launch({
    executablePath: CHROMIUM,
    ignoreDefaultArgs: true,
    args: [
      '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      `--user-data-dir=${join(scratch, 'profile')}`, '--window-size=1500,1000', 'about:blank',
    ],
    defaultViewport: { width: 1500, height: 1000 },
  });
});

after(async () => {
  await browser?.close();
  server?.close();
  if (scratch) rmSync(scratch, { recursive: true, force: true });
});

/// A new tab on the page (with `hash`), its errors collected, once it drew.
async function open(hash = '') {
  const page = await browser.newPage();
  page.setDefaultTimeout(WAIT_MS);
  page.errors = [];
  page.on('pageerror', (e) => page.errors.push(String(e)));
  page.on('console', (m) => m.type() === 'error' && page.errors.push(m.text()));
  await page.goto(site + hash);
  await page.waitForFunction(() => window.ertrace !== undefined);
  await idle(page);
  return page;
}

function idle(page) {
  return page.evaluate(() => window.ertrace.whenIdle());
}

/// How the display's canvas differs from the PNG `file` (an image the same size, each
/// pixel the same RGB): the number of differing pixels, or the sizes if they differ.
/// The PNG is decoded by the browser without colour conversion.
async function compareCanvas(page, file, pngBytes) {
  const b64 = (pngBytes ?? readFileSync(file)).toString('base64');
  return page.evaluate(async (b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }), {
      colorSpaceConversion: 'none', premultiplyAlpha: 'none',
    });
    const c = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
    c.drawImage(bitmap, 0, 0);
    const want = c.getImageData(0, 0, bitmap.width, bitmap.height);
    const canvas = document.getElementById('display');
    const have = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height);
    if (have.width !== want.width || have.height !== want.height) {
      return `canvas ${have.width}x${have.height}, PNG ${want.width}x${want.height}`;
    }
    let differ = 0;
    for (let k = 0; k < have.data.length; k += 4) {
      if (have.data[k] !== want.data[k] || have.data[k + 1] !== want.data[k + 1] ||
          have.data[k + 2] !== want.data[k + 2] || want.data[k + 3] !== 255) differ++;
    }
    return differ;
  }, b64);
}

/// Two PNGs' pixels (decoded by the browser), compared: the number that differ.
async function comparePngs(page, a, b) {
  return page.evaluate(async (a, b) => {
    const decode = async (b64) => {
      const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
      const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }), {
        colorSpaceConversion: 'none', premultiplyAlpha: 'none',
      });
      const c = new OffscreenCanvas(bitmap.width, bitmap.height).getContext('2d');
      c.drawImage(bitmap, 0, 0);
      return c.getImageData(0, 0, bitmap.width, bitmap.height);
    };
    const [x, y] = [await decode(a), await decode(b)];
    if (x.width !== y.width || x.height !== y.height) return `${x.width}x${x.height} against ${y.width}x${y.height}`;
    let differ = 0;
    for (let k = 0; k < x.data.length; k += 4) {
      if (x.data[k] !== y.data[k] || x.data[k + 1] !== y.data[k + 1] || x.data[k + 2] !== y.data[k + 2]) differ++;
    }
    return differ;
  }, Buffer.from(a).toString('base64'), Buffer.from(b).toString('base64'));
}

async function text(page, selector) {
  return page.$eval(selector, (e) => e.textContent);
}

/// Types `value` into the editor as a person's edit does (an `input` event).
async function edit(page, value) {
  await page.$eval('#text', (t, v) => {
    t.value = v;
    t.dispatchEvent(new Event('input'));
  }, value);
  await idle(page);
}

test("scenes/lab.toml's display is the render CLI's PNG, bit for bit", async () => {
  const page = await open();
  assert.equal(await page.$eval('#scene', (s) => s.value), 'lab');
  assert.equal(await compareCanvas(page, join(scratch, 'lab.png')), 0);
  assert.match(await text(page, '#status-method'), /^320×240 rgb888 · direct\/auto\/exact · center/);
  assert.match(await text(page, '#status-time'), /ms a frame in this browser on this machine, not on a board/);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test("scenes/bounce.toml stepped frame by frame is the CLI's --output-frames", async () => {
  const page = await open();
  await page.select('#scene', 'bounce');
  await idle(page);
  await page.evaluate(() => window.ertrace.show(0));
  await idle(page);
  let partial = 0;
  for (let k = 0; k < 30; k++) {
    if (k > 0) {
      await page.click('#forward');
      await idle(page);
    }
    const file = join(scratch, 'bounce', `${String(k + 1).padStart(4, '0')}.png`);
    assert.equal(await compareCanvas(page, file), 0, `frame ${k + 1}`);
    const line = await text(page, '#status-frame');
    assert.match(line, new RegExp(`^frame ${k + 1}/30 paused · traced \\d+ px`), line);
    if (!line.includes('whole frame')) partial++;
  }
  assert.ok(partial >= 20, `only ${partial} of 30 frames drawn in part`);
  // The overlay marks what the last frame traced and sent.
  const marked = await page.$eval('#overlay', (c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let k = 3; k < d.length; k += 4) if (d[k]) n++;
    return n;
  });
  assert.ok(marked > 0, 'no pixel marked');
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('a scene with a bad field shows that field and keeps the last picture', async () => {
  const page = await open();
  const lab = await page.$eval('#text', (t) => t.value);
  const picture = () => page.$eval('#display', (c) => c.toDataURL());
  const before = await picture();
  await edit(page, lab.replace('radius = ', 'radius = -'));
  const error = await text(page, '#error');
  assert.match(error, /sphere\[0\]\.radius: radius must be greater than 0/);
  assert.equal(await picture(), before, 'the picture changed');
  // Without a line from the parser, the gutter marks the table the field names.
  const sphereLine = lab.split('\n').findIndex((l) => l.startsWith('[[sphere]]')) + 1;
  assert.equal(await text(page, '#gutter .bad'), String(sphereLine));
  // A syntax error is shown at its line.
  await edit(page, `${lab}\n[camera\n`);
  const line = lab.split('\n').length + 1; // lab.toml ends with a newline
  assert.match(await text(page, '#error'), new RegExp(`^line ${line}: `));
  assert.equal(await text(page, '#gutter .bad'), String(line));
  assert.equal(await picture(), before);
  // Fixed: drawn again, the error gone.
  await edit(page, lab.replace('[255, 64, 64]', '[64, 64, 255]'));
  assert.equal(await page.$eval('#error', (e) => e.hidden), true);
  assert.notEqual(await picture(), before);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('an edit abandons the frame being drawn and draws the new text', async () => {
  const page = await open();
  await page.select('#scene', 'mirrors');
  await idle(page);
  const edited = (await page.$eval('#text', (t) => t.value)).replace(/^max_depth = 3$/m, 'max_depth = 1');
  // A slow frame (adaptive sampling, mirrors) asked for, and the text edited while it
  // is drawn.
  await page.evaluate((edited) => {
    const sampling = document.getElementById('sampling');
    sampling.value = 'adaptive:4';
    sampling.dispatchEvent(new Event('change'));
    const text = document.getElementById('text');
    text.value = edited;
    text.dispatchEvent(new Event('input'));
    window.ertrace.textChanged();
  }, edited);
  await idle(page);
  assert.equal(await page.evaluate(() => window.ertrace.state.cancelled), 1);
  const picture = await page.$eval('#display', (c) => c.toDataURL());
  // The same text and view drawn on a page that drew nothing before.
  const fresh = await open(new URL(await page.evaluate(() => window.ertrace.shareLink())).hash);
  assert.equal(await fresh.$eval('#display', (c) => c.toDataURL()), picture);
  assert.deepEqual([...page.errors, ...fresh.errors], []);
  for (const p of [page, fresh]) await p.close();
});

test("the dithered 128×64 model, OLED blue at the preview's scale, is docs/lab-128x64-binary-dither.png", async () => {
  const page = await open();
  await page.select('#panel', '128x64');
  await page.select('#model', 'binary-dither');
  await idle(page);
  assert.equal(await page.$eval('#theme', (s) => s.value), 'oled-blue');
  assert.equal(await page.$eval('#bayer', (s) => s.value), '8');
  const png = await page.evaluate(async () => Array.from(await window.ertrace.png(4)));
  const docs = readFileSync(join(ROOT, 'docs/lab-128x64-binary-dither.png'));
  assert.equal(await comparePngs(page, Buffer.from(png), docs), 0);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('a share link carries the scene and the view', async () => {
  const page = await open();
  await page.select('#board', '1'); // the SSD1306 Pico
  await edit(page, (await page.$eval('#text', (t) => t.value)).replace('[255, 64, 64]', '[90, 200, 90]'));
  const link = await page.evaluate(() => window.ertrace.shareLink());
  const picture = await page.$eval('#display', (c) => c.toDataURL());
  const shared = await open(new URL(link).hash);
  assert.equal(await shared.$eval('#text', (t) => t.value), await page.$eval('#text', (t) => t.value));
  assert.equal(await shared.$eval('#model', (s) => s.value), 'binary-dither');
  assert.equal(await shared.$eval('#integer', (s) => s.checked), true);
  assert.equal(await shared.$eval('#display', (c) => c.toDataURL()), picture);
  assert.deepEqual([...page.errors, ...shared.errors], []);
  // A fragment that inflates past the loader's 1 MiB is refused while it is read.
  const bomb = await page.evaluate(async () => {
    const big = new Blob(['#'.repeat((1 << 20) + 1)]).stream().pipeThrough(new CompressionStream('deflate-raw'));
    const bytes = new Uint8Array(await new Response(big).arrayBuffer());
    let s = '';
    for (const b of bytes) s += String.fromCharCode(b);
    return btoa(s).replaceAll('+', '-').replaceAll('/', '_').replace(/=+$/, '');
  });
  const refused = await open(`#scene=${bomb}`);
  assert.match(await text(refused, '#share-note'), /share link: the shared scene is more than 1048576 bytes/);
  assert.equal(await refused.$eval('#scene', (s) => s.value), 'lab', 'the default scene instead');
  for (const p of [page, shared, refused]) await p.close();
});

test('a board preset sets its panel, format and method; the difference view counts', async () => {
  const page = await open();
  await page.select('#scene', 'circling');
  await page.select('#board', '0'); // the ST7789 Pico: integer kernel, Rgb565
  await idle(page);
  assert.equal(await page.$eval('#panel', (s) => s.value), '240x240');
  assert.match(await text(page, '#status-method'), /^240×240 rgb565 · integer\/direct\/auto\/exact · center$/);
  await page.click('#stage'); // the keys act where the focus is not in a picker
  await page.keyboard.press('d');
  await idle(page);
  assert.match(await text(page, '#status-frame'), /^D: \d+ px differ from direct\/robust\/exact/);
  assert.deepEqual(page.errors, []);
  await page.close();
});

test('the screenshot', { skip: !UPDATE && 'WEB_UPDATE=1 writes docs/web.png' }, async () => {
  const page = await open();
  await page.setViewport({ width: 1500, height: 680 });
  await page.select('#scene', 'bounce');
  await page.select('#board', '3'); // Pico 2: f32, Rgb565 on a 240×240 ST7789
  await page.select('#scale', '2');
  await idle(page);
  await page.evaluate(() => window.ertrace.show(11));
  await idle(page);
  await page.click('#forward');
  await idle(page);
  await page.screenshot({ path: join(ROOT, 'docs/web.png') });
  await page.close();
});
