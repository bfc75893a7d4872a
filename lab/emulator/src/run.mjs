// Runs one board example's firmware in rp2040js for a number of frames of its main loop
// and writes what the panel showed and when:
//
//   node src/run.mjs --board simple|ssd1306 --elf FIRMWARE --frames N --pictures M --out DIR [--pc-part P]
//
// DIR/BOARD.json: the clock, the wire rate, per frame its cycles (the firmware's own
// timing interval, the whole loop iteration, the part before the first byte of the
// frame reached the display), the microseconds the firmware read from the timer, the
// pixels or bytes sent; the cycles by function (the profile); rp2040js's warnings.
// DIR/BOARD-K-*.raw: the first M frames' pictures (see `capture` below).
// DIR/BOARD-pc.txt (with --pc-part): part P of the later frames by instruction address,
// per frame; DIR/BOARD-pc.profile: the same in the format of `cycle_model --profile`
// (a label holding `frames N` and `clk HZ`, then address, executions and cycles summed over
// the N later frames), which `lab/examples/profile_lines.rs` resolves into source lines.
//
// The main loop of both examples reads the timer at the start of a frame and after it
// (`timer.get_counter()`); the display's start-up before it reads the timer too (its
// delays), and sends no picture. So the loop's first read is the last one before the
// first picture byte, and from there the reads alternate: start of frame k, end of
// frame k, start of frame k + 1, …

import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseArgs } from 'node:util';
import { Pico, Warnings } from './pico.mjs';
import { St7789 } from './st7789.mjs';
import { Ssd1306 } from './ssd1306.mjs';

const { values: args } = parseArgs({
  options: {
    board: { type: 'string' },
    elf: { type: 'string' },
    frames: { type: 'string', default: '12' },
    pictures: { type: 'string', default: '12' },
    out: { type: 'string' },
    // Where the later frames' time goes by instruction: BOARD-pc.txt, the hottest
    // addresses of one part (0: before the first window, 1: the windows, 2: after), and
    // BOARD-pc.profile, the same for lab/examples/profile_lines.rs.
    'pc-part': { type: 'string' },
  },
});
if (!args.board || !args.elf || !args.out) {
  console.error('usage: node src/run.mjs --board simple|ssd1306 --elf FIRMWARE [--frames N] [--pictures M] --out DIR');
  process.exit(2);
}
const frames = Number(args.frames);
const pictures = Math.min(Number(args.pictures), frames);
mkdirSync(args.out, { recursive: true });

const warnings = new Warnings();
const pico = new Pico(readFileSync(args.elf), warnings);

// Profile buckets: the start-up (until the first timer read; not reported), then per
// frame kind (frame 0; frames 1 and later) its three parts: before its first byte to
// the display (the per-frame set-up), from there to the end of the frame as the
// firmware times it, and from there to the next frame's start (simple: the status
// line).
const PARTS = ['before the first window', 'windows (trace and send)', 'after the frame (status line)'];
const bucketOf = (k, part) => 1 + (k === 0 ? 0 : 3) + part;

// The display; `frameByte()` at each frame's first byte to it (simple: its first
// window, CASET; the SSD1306: its first transaction), `pictureByte()` at the first
// picture byte (the loop has started by then).
let display;
let sent = () => 0;
let wire;
if (args.board === 'simple') {
  display = new St7789(240, 240);
  const dc = pico.mcu.gpio[8];
  const cs = pico.mcu.gpio[9];
  const spi = pico.spi(1, (value) => {
    // A byte with CS high is not the controller's.
    if (!cs.outputValue) display.byte(value, dc.outputValue);
  });
  display.onCommand = (cmd) => {
    if (cmd === 0x2a) {
      pictureByte();
      frameByte();
    }
  };
  sent = () => display.pixels;
  wire = () => ({ what: 'SPI1', hz: spi.clockFrequency });
} else if (args.board === 'ssd1306') {
  display = new Ssd1306(0x3c);
  const device = {
    start: () => {
      display.start();
      frameByte();
    },
    byte: (v) => {
      const before = display.dataBytes;
      display.byte(v);
      if (display.dataBytes !== before) pictureByte();
    },
  };
  const i2c = pico.i2c(0, 0x3c, device);
  sent = () => display.dataBytes;
  wire = () => ({ what: 'I2C0', hz: pico.clkSys / pico.i2cPeriod(), sclPeriodCycles: pico.i2cPeriod(), speed: i2c.speed });
} else {
  console.error(`unknown board ${args.board}`);
  process.exit(2);
}

// The timer reads: { cycles, us, sent } each; `loop` the index of frame 0's start once
// known; `firstSinceRead` the cycles of the first byte to the display since the last read.
const reads = [];
let loop = null;
let firstSinceRead = null;
const frameFirst = [];
function pictureByte() {
  if (loop !== null) return;
  if (reads.length === 0) throw new Error('a picture byte before any timer read');
  loop = reads.length - 1;
  frameFirst[0] = firstSinceRead ?? pico.cycles;
  // What ran since the frame's first byte (the SSD1306's commands before its data).
  pico.bucket = bucketOf(0, 1);
}
function frameByte() {
  firstSinceRead ??= pico.cycles;
  if (loop === null) return;
  const i = reads.length - 1 - loop;
  const k = Math.floor(i / 2);
  if (i % 2 === 0 && frameFirst[k] === undefined) {
    frameFirst[k] = pico.cycles;
    pico.bucket = bucketOf(k, 1);
  }
}

const capture = []; // [k] = { frame: picture at the frame's end, status: at the next start }
pico.onTimerRead = (cycles, us) => {
  reads.push({ cycles, us, sent: sent(), wire: pico.wireCycles });
  firstSinceRead = null;
  if (loop === null) {
    // Until the picture starts, each read may be frame 0's start: what ran since the
    // last read was start-up after all, which is not profiled.
    const stride = pico.fns.length + 1;
    const frame0 = bucketOf(0, 0);
    pico.profile.fill(0, frame0 * stride, (frame0 + 1) * stride);
    pico.bucket = frame0;
    return;
  }
  const i = reads.length - 1 - loop; // 1: end of frame 0, 2: start of frame 1, …
  const k = Math.floor(i / 2);
  if (i % 2 === 1) {
    // The end of frame k: simple's picture without its status line (the frame
    // restored the last one's), the SSD1306's with it (drawn before the flush).
    if (k < pictures) capture[k] = { frame: display.picture() };
    pico.bucket = bucketOf(k, 2);
  } else {
    // The start of frame k: simple's picture of frame k - 1 with its status line.
    if (k - 1 < pictures && args.board === 'simple') capture[k - 1].status = display.picture();
    pico.bucket = bucketOf(k, 0);
  }
};

if (args['pc-part'] !== undefined) pico.pcProfile(bucketOf(1, Number(args['pc-part'])));

const started = Date.now();
const cpu = process.cpuUsage();
pico.run(() => loop !== null && reads.length - 1 - loop >= 2 * frames, 4e9);
const seconds = (Date.now() - started) / 1000;
const cpuSeconds = process.cpuUsage(cpu).user / 1e6;

const perFrame = [];
for (let k = 0; k < frames; k++) {
  const t0 = reads[loop + 2 * k];
  const t1 = reads[loop + 2 * k + 1];
  const next = reads[loop + 2 * k + 2];
  perFrame.push({
    k,
    cycles: t1.cycles - t0.cycles,
    loopCycles: next.cycles - t0.cycles,
    firstByteCycles: frameFirst[k] === undefined ? null : frameFirst[k] - t0.cycles,
    us: (t1.us - t0.us) >>> 0,
    sent: t1.sent - t0.sent,
    wireCycles: t1.wire - t0.wire,
    loopWireCycles: next.wire - t0.wire,
  });
}

const stride = pico.fns.length + 1;
const profile = {};
for (const [kind, first] of [['frame 0', 0], ['later frames', 3]]) {
  profile[kind] = PARTS.map((part, p) => {
    const b = 1 + first + p;
    const fns = [];
    for (let f = 0; f < stride; f++) {
      const c = pico.profile[b * stride + f];
      if (c > 0) {
        const fn = pico.fns[f];
        fns.push(fn ? { fn: fn.name, at: `0x${fn.start.toString(16)}`, cycles: c } : { fn: '(outside the functions)', cycles: c });
      }
    }
    fns.sort((a, b) => b.cycles - a.cycles);
    return { part, fns };
  });
}

const result = {
  board: args.board,
  clkSys: pico.clkSys,
  wire: wire(),
  frames: perFrame,
  cyclesTotal: pico.cycles,
  instructions: pico.instructions,
  bootCycles: reads[loop].cycles,
  seconds,
  cpuSeconds,
  profile,
  warnings: warnings.summary(),
};
writeFileSync(join(args.out, `${args.board}.json`), `${JSON.stringify(result, null, 1)}\n`);
for (let k = 0; k < pictures; k++) {
  for (const [what, pic] of Object.entries(capture[k])) {
    if (!pic) throw new Error(`frame ${k}: the ${what} picture has pixels never written`);
    writeFileSync(join(args.out, `${args.board}-${k}-${what}.raw`), Buffer.from(pic.buffer, pic.byteOffset, pic.byteLength));
  }
}
if (pico.pcCycles) {
  const rows = [];
  pico.pcCycles.forEach((c, i) => {
    if (c > 0) rows.push([c, 0x10000000 + 2 * i]);
  });
  rows.sort((a, b) => b[0] - a[0]);
  const perFrame = (c) => (c / Math.max(1, frames - 1)).toFixed(0);
  const text = rows.map(([c, at]) => `0x${at.toString(16)} ${perFrame(c)} ${pico.fns[pico.fnAt[(at - 0x10000000) >> 1]].name}`);
  const name = (i) => (pico.fns[i] ? pico.fns[i].name : '(outside)');
  const calls = [...pico.calls].sort((a, b) => b[1] - a[1]);
  for (const [key, n] of calls) {
    const [callee, caller] = key.split(' ').map(Number);
    text.push(`calls ${perFrame(n)} ${name(callee)} <- ${name(caller)}`);
  }
  writeFileSync(join(args.out, `${args.board}-pc.txt`), `${text.join('\n')}\n`);
  const label = `${args.board} part ${args['pc-part']} frames ${Math.max(1, frames - 1)} clk ${pico.clkSys}`;
  const profile = rows
    .sort((a, b) => a[1] - b[1])
    .map(([c, at]) => `${label} | ${at.toString(16)} ${pico.pcCount[(at - 0x10000000) >> 1]} ${c}`);
  writeFileSync(join(args.out, `${args.board}-pc.profile`), `${profile.join('\n')}\n`);
}
const ms = (c) => ((c / pico.clkSys) * 1e3).toFixed(1);
console.log(
  `${args.board}: ${frames} frames, ${(pico.instructions / 1e6).toFixed(0)} M instructions in ${seconds.toFixed(1)} s ` +
    `(${cpuSeconds.toFixed(1)} s of CPU: ${(pico.instructions / cpuSeconds / 1e6).toFixed(1)} M a second); clk_sys ${pico.clkSys / 1e6} MHz, ` +
    `${result.wire.what} ${(result.wire.hz / 1e6).toFixed(3)} MHz; frame ms: ${perFrame.map((f) => ms(f.loopCycles)).join(' ')}`,
);
