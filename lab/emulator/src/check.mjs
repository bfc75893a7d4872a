// Compares what the firmware showed in rp2040js (`run.mjs`'s output) with the host:
//
//   node src/check.mjs --dir DIR --cli CLI_DIR --pictures N --data FIGURES.json [--update DOCS_ROOT]
//
// Every pixel of frames 0 … N-1, and what each status line says:
// - `simple` (ST7789, RGB565): the panel at each frame's end (the last status line
//   re-traced) against the render CLI's PNG of that frame, quantised to RGB565 as
//   embedded-graphics does, and against the host's draw of the board's own `frame.rs`
//   (`pico_frames`); the panel with the frame's status line against the host's, whose
//   line carries the frame time the firmware read. The line read back through the font
//   says the integer kernel, the frame rate of the time the firmware read and the share
//   of the panel the SPI stream carried.
// - `ssd1306` (1 bit, dithered): the panel after each flush, status line drawn over it,
//   against the host's draw of its `frame.rs`; the line read back says the last frame's
//   rate (none on the first) and the host's share.
// The frame times (cycles of the whole loop iteration) against FIGURES.json within ±2 %,
// or, with --update, written there and into the docs' marker blocks.

import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseArgs } from 'node:util';
import { readPng, rgb565 } from './png.mjs';
import { docs } from './report.mjs';

const { values: args } = parseArgs({
  options: {
    dir: { type: 'string' },
    cli: { type: 'string' },
    pictures: { type: 'string', default: '12' },
    data: { type: 'string' },
    update: { type: 'string' },
    tolerance: { type: 'string', default: '0.02' },
  },
});
const N = Number(args.pictures);
const failures = [];
const fail = (msg) => {
  failures.push(msg);
  console.log(`FAIL ${msg}`);
};

const raw = (name) => readFileSync(join(args.dir, name));
const u16 = (buf) => new Uint16Array(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength));

// The font: 60 pixels a glyph, '#' on, as a key.
const glyphs = new Map();
{
  const lines = readFileSync(join(args.dir, 'font-6x10.txt'), 'latin1').trim().split('\n');
  for (let i = 0; i + 10 < lines.length + 1; i += 11) {
    glyphs.set(lines.slice(i + 1, i + 11).join(''), String.fromCharCode(Number(lines[i])));
  }
}

/** The text in 6×10 cells from (x0, y0) of a `width`-wide picture: `on(p)`/`off(p)` say
 * what a pixel of a glyph is; the text ends at the first cell that is no glyph, and
 * trailing blanks are dropped. */
function readText(pic, width, x0, y0, on, off) {
  let text = '';
  for (let x = x0; x + 6 <= width; x += 6) {
    let key = '';
    for (let y = y0; y < y0 + 10; y++) {
      for (let dx = 0; dx < 6; dx++) {
        const p = pic[y * width + x + dx];
        if (on(p)) key += '#';
        else if (off(p)) key += '.';
        else return text.trimEnd();
      }
    }
    const c = glyphs.get(key);
    if (c === undefined) break;
    text += c;
  }
  return text.trimEnd();
}

/** The differing pixels of two pictures; a few listed, a picture of them written. */
function compare(what, want, got, width, name, fmt) {
  let n = 0;
  const first = [];
  for (let i = 0; i < want.length; i++) {
    if (want[i] !== got[i]) {
      if (first.length < 5) first.push(`(${i % width}, ${Math.floor(i / width)}): want ${fmt(want[i])}, got ${fmt(got[i])}`);
      n++;
    }
  }
  if (n > 0) {
    const height = want.length / width;
    const ppm = Buffer.alloc(width * height * 3);
    for (let i = 0; i < want.length; i++) {
      const d = want[i] !== got[i];
      ppm.set(d ? [255, 0, 0] : [40, 40, 40], i * 3);
    }
    const file = join(args.dir, `diff-${name}.ppm`);
    writeFileSync(file, Buffer.concat([Buffer.from(`P6\n${width} ${height}\n255\n`), ppm]));
    fail(`${what}: ${n} pixels differ (${file}): ${first.join('; ')}`);
  }
  return n;
}

const hex = (v) => `0x${v.toString(16).padStart(4, '0')}`;
const tenths = (us) => Math.floor(10_000_000 / Math.max(us, 1));
const rate = (us) => `${Math.floor(tenths(us) / 10)}.${tenths(us) % 10}`;
const hostLines = (board) =>
  readFileSync(join(args.dir, `host-${board}.txt`), 'utf8')
    .trimEnd()
    .split('\n')
    .map((l) => {
      const [head, status] = l.split('\t');
      const [k, sent, traced] = head.split(' ').map(Number);
      return { k, sent, traced, status };
    });

const runs = {};
const statusLines = {};

// --- simple ---
{
  const emu = JSON.parse(readFileSync(join(args.dir, 'simple.json'), 'utf8'));
  runs.simple = emu;
  const host = hostLines('simple');
  const W = 240;
  const pixels = W * W;
  statusLines.simple = [];
  for (let k = 0; k < N; k++) {
    const frame = u16(raw(`simple-${k}-frame.raw`));
    const status = u16(raw(`simple-${k}-status.raw`));
    const png = readPng(readFileSync(join(args.cli, `${String(k + 1).padStart(4, '0')}.png`)));
    if (png.width !== W || png.height !== W) fail(`simple frame ${k}: the CLI's PNG is ${png.width}×${png.height}`);
    const cli = new Uint16Array(pixels);
    for (let i = 0; i < pixels; i++) cli[i] = rgb565(png.rgb[3 * i], png.rgb[3 * i + 1], png.rgb[3 * i + 2]);
    compare(`simple frame ${k} against the render CLI`, cli, frame, W, `simple-${k}-cli`, hex);
    compare(`simple frame ${k} against the host's frame.rs`, u16(raw(`host-simple-${k}-frame.raw`)), frame, W, `simple-${k}-frame`, hex);
    compare(`simple frame ${k} with its status line against the host's`, u16(raw(`host-simple-${k}-status.raw`)), status, W, `simple-${k}-status`, hex);

    const f = emu.frames[k];
    const text = readText(status, W, 2, 2, (p) => p === 0xffff, (p) => p === 0);
    statusLines.simple.push(text);
    const m = /^integer (\d+)\.(\d) fps sent (\d+)%$/.exec(text);
    const want = `integer ${rate(f.us)} fps sent ${Math.floor((f.sent * 100) / pixels)}%`;
    if (!m || text !== want) fail(`simple frame ${k}: the status line reads "${text}", the firmware's time and the SPI stream say "${want}"`);
    if (host[k].status !== text) fail(`simple frame ${k}: the status line reads "${text}", the host drew "${host[k].status}"`);
    if (host[k].sent !== f.sent) fail(`simple frame ${k}: ${f.sent} pixels on SPI, the host's frame sent ${host[k].sent}`);
    const cycleUs = (f.cycles / emu.clkSys) * 1e6;
    if (Math.abs(cycleUs - f.us) > 1) fail(`simple frame ${k}: the timer read ${f.us} µs, the cycles say ${cycleUs.toFixed(1)}`);
  }
  console.log(`simple: frames 0-${N - 1}: every pixel compared (CLI, host frame.rs, status lines); status lines: ${statusLines.simple.map((t) => `"${t}"`).join(', ')}`);
}

// --- ssd1306 ---
{
  const emu = JSON.parse(readFileSync(join(args.dir, 'ssd1306.json'), 'utf8'));
  runs.ssd1306 = emu;
  const host = hostLines('ssd1306');
  const W = 128;
  const pixels = W * 64;
  statusLines.ssd1306 = [];
  for (let k = 0; k < N; k++) {
    const frame = new Uint8Array(raw(`ssd1306-${k}-frame.raw`));
    compare(`ssd1306 frame ${k} with its status line against the host's frame.rs`, new Uint8Array(raw(`host-ssd1306-${k}-frame.raw`)), frame, W, `ssd1306-${k}-frame`, String);
    const text = readText(frame, W, 0, 0, (p) => p === 1, (p) => p === 0);
    statusLines.ssd1306.push(text);
    const share = Math.floor((host[k].sent * 100) / pixels);
    const want = k === 0 ? `int ${share}%` : `int ${rate(emu.frames[k - 1].us)}fps ${share}%`;
    if (text !== want) fail(`ssd1306 frame ${k}: the status line reads "${text}", the firmware's time and the host's share say "${want}"`);
    if (host[k].status !== text) fail(`ssd1306 frame ${k}: the status line reads "${text}", the host drew "${host[k].status}"`);
  }
  console.log(`ssd1306: frames 0-${N - 1}: every pixel compared (host frame.rs, status lines); status lines: ${statusLines.ssd1306.map((t) => `"${t}"`).join(', ')}`);
}

// --- timing ---
const tolerance = Number(args.tolerance);
if (args.update) {
  const figures = {};
  for (const [board, emu] of Object.entries(runs)) {
    figures[board] = {
      clkSys: emu.clkSys,
      wire: emu.wire,
      frames: emu.frames.map((f) => [f.k, f.cycles, f.loopCycles, f.firstByteCycles, f.us, f.sent]),
    };
  }
  if (failures.length === 0) {
    writeFileSync(args.data, `${JSON.stringify({ fields: ['k', 'cycles', 'loopCycles', 'firstByteCycles', 'us', 'sent'], ...figures })}\n`);
    docs(args.update, runs, statusLines);
    console.log(`written: ${args.data} and the docs' pico_emu blocks`);
  }
} else if (args.data) {
  const figures = JSON.parse(readFileSync(args.data, 'utf8'));
  for (const [board, emu] of Object.entries(runs)) {
    for (const f of emu.frames) {
      const stored = figures[board].frames[f.k];
      if (!stored) continue;
      const loopCycles = stored[2];
      const off = f.loopCycles / loopCycles - 1;
      if (Math.abs(off) > tolerance) {
        fail(`${board} frame ${f.k}: ${f.loopCycles} cycles, the committed figures ${loopCycles} (${(off * 100).toFixed(1)} %; bash .ci/pico-emu --update)`);
      }
    }
  }
  console.log(`frame times against ${args.data}: within ±${tolerance * 100} % unless listed`);
}

if (failures.length) {
  console.log(`\n${failures.length} failures`);
  process.exit(1);
}
console.log('pico-emu: every pixel equal, every status line as measured');
