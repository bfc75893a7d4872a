// The measured figures as Markdown, into the marker blocks
// `<!-- pico_emu:begin … -->` … `<!-- pico_emu:end -->` of docs/firmware.md and the two
// board READMEs.

import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

// What a function's cycles count as, by its (demangled) name; the first match wins.
const KINDS = [
  ['soft `f64`', /^__aeabi_(d[a-z0-9]+|i2d|ui2d|l2d|ul2d|f2d)$|::__(add|sub|mul|div)df3$/],
  ['soft `f32`', /^__aeabi_(f[a-z0-9]+|i2f|ui2f)$|::__(add|sub|mul|div)sf3$|^fm(ax|in)f?$/],
  ['64-bit multiplication', /^__aeabi_lmul$|__muldi3/],
  ['64-bit shifts', /^__aeabi_(llsl|llsr|lasr)$/],
  ['integer division', /div|_div_rem/],
  ['`memcpy`, `memset`', /mem(cpy|set|clr|move|cmp)/],
  ['`libm`', /^libm::/],
  ['the kernel', /embedded_raytracer::/],
  ['pixels (the kernel inlined into the pixel loop)', /^<(core::iter|&mut I|I as core::iter)|::send_pixels$/],
  ['driver and HAL', /mipidsi|ssd1306|display_interface|rp2040_hal|embedded_hal|::dma_spi::/],
  ['text', /embedded_graphics|core::fmt|flt2dec|heapless|::status$|::show$/],
];
const LEGEND =
  'soft `f64`: compiler-builtins\' `__aeabi_d*`, `__muldf3`, `__adddf3`, `__divdf3` and the ' +
  'conversions to and from `f64`; soft `f32` likewise; 64-bit multiplication: `__aeabi_lmul`; ' +
  '64-bit shifts: `__aeabi_llsl`, `__aeabi_llsr`, `__aeabi_lasr`; integer division: ' +
  '`__aeabi_uidiv`, `__aeabi_uldivmod` and their helpers; other: `__clzsi2` (the soft float\'s ' +
  'normalisation) and the rest; `libm`: the motion\'s `sinf`/`cosf`, ' +
  '`sqrt`; the kernel: `embedded_raytracer`\'s functions that were not inlined; pixels: ' +
  'the loop that pulls pixels and turns them into wire bytes (mipidsi\'s `send_pixels`, with ' +
  'the status line\'s pixels too) and the `core::iter` adapters (`Chain::next`, `Map::fold`) ' +
  'the drivers pull from, the kernel\'s per-pixel work (the integer kernel\'s discriminant, ' +
  'root and shade) inlined into them (`lab/emulator/src/run.mjs --pc-part 1` profiles them ' +
  'by instruction); driver and HAL: ' +
  '`mipidsi`, `ssd1306`, `display-interface`, `rp2040-hal`, `simple`\'s `dma_spi` — pixels ' +
  'into wire bytes, and the waits for the wire; text: the status line\'s font and formatting.';
const kindOf = (fn) => (KINDS.find(([, re]) => re.test(fn)) || ['other'])[0];

const ms = (cycles, clk) => (cycles / clk) * 1e3;
const f1 = (x) => x.toFixed(1);
const fps = (cycles, clk) => f1(clk / cycles);
const pct = (part, whole) => `${Math.round((part / whole) * 100)} %`;
const stats = (xs) => ({
  min: Math.min(...xs),
  max: Math.max(...xs),
  mean: xs.reduce((a, b) => a + b, 0) / xs.length,
});
const code = (s) => `\`${s.replace(/`/g, "'")}\``;
const short = (fn) => (fn.length > 110 ? `${fn.slice(0, 107)}…` : fn);

function byKind(fns) {
  const m = new Map();
  for (const { fn, cycles } of fns) m.set(kindOf(fn), (m.get(kindOf(fn)) || 0) + cycles);
  return [...m].sort((a, b) => b[1] - a[1]);
}

/** The per-frame figures of a run: first frame, later frames. */
function summary(run) {
  const clk = run.clkSys;
  const later = run.frames.slice(1);
  return {
    clk,
    first: run.frames[0],
    loop: stats(later.map((f) => f.loopCycles)),
    timed: stats(later.map((f) => f.cycles)),
    before: stats(later.map((f) => f.firstByteCycles)),
    wire: stats(later.map((f) => f.loopWireCycles)),
    n: later.length,
  };
}

function table(runs) {
  const s = summary(runs.simple);
  const o = summary(runs.ssd1306);
  const row = (name, wire, x) =>
    `| ${name} | ${wire} | ${f1(ms(x.first.loopCycles, x.clk))} ms (${fps(x.first.loopCycles, x.clk)} fps) | ` +
    `${f1(ms(x.loop.min, x.clk))} / ${f1(ms(x.loop.mean, x.clk))} / ${f1(ms(x.loop.max, x.clk))} ms ` +
    `(${fps(x.loop.mean, x.clk)} fps at the mean) | ${f1(ms(x.first.loopWireCycles, x.clk))} ms; ` +
    `${f1(ms(x.wire.mean, x.clk))} ms |`;
  return [
    `| example | the wire (from its registers) | first frame (whole) | later frames (1–${s.n}): min / mean / max | on the wire: first; later, mean |`,
    '|---|---|---|---|---|',
    row('`simple` (ST7789 240×240)', `SPI1 ${f1(runs.simple.wire.hz / 1e6)} MHz`, s),
    row('`rp2040-ssd1306` (SSD1306 128×64)', `I²C0 ${f1(runs.ssd1306.wire.hz / 1e3)} kHz`, o),
  ].join('\n');
}

const NOT_MODELLED =
  'rp2040js counts the Cortex-M0+ cycles of each instruction and nothing else: it has no ' +
  'core 1, and it does not model the XIP flash: no cache misses, no wait states — code ' +
  'and constants in flash cost what they would from RAM. A Pico is slower than these ' +
  'figures, not faster; how much depends on how the hot loops fit the 16 KiB XIP cache.';

// The parts of a frame, by board: the run's three profile buckets.
const PART_NAMES = {
  simple: ['before the first window', 'the windows: trace and send', 'the status line'],
  ssd1306: ['drawing into the buffer', 'the flush over I²C', 'the rest of the loop'],
};

/** A later frame's cycles by kind of code (rows, the largest first) and part (columns),
 * per frame. */
function matrix(run, board) {
  const clk = run.clkSys;
  const n = run.frames.length - 1;
  const parts = run.profile['later frames'];
  const cells = new Map();
  parts.forEach((part, p) => {
    for (const { fn, cycles } of part.fns) {
      const k = kindOf(fn);
      if (!cells.has(k)) cells.set(k, parts.map(() => 0));
      cells.get(k)[p] += cycles / n;
    }
  });
  const keep = parts.map((part) => part.fns.some((f) => f.cycles / n / clk > 1e-4));
  const names = PART_NAMES[board].filter((_, p) => keep[p]);
  const totals = parts.map((part) => part.fns.reduce((a, f) => a + f.cycles, 0) / n);
  const all = totals.reduce((a, b) => a + b, 0);
  const rows = [...cells].sort((a, b) => b[1].reduce((x, y) => x + y) - a[1].reduce((x, y) => x + y));
  const cell = (c) => (c / clk >= 5e-5 ? (ms(c, clk)).toFixed(1) : '');
  const out = [
    `| ms a frame | ${names.join(' | ')} | the frame |`,
    `|---|${names.map(() => '---:').join('|')}|---:|`,
    `| **all** | ${totals.filter((_, p) => keep[p]).map((c) => `**${cell(c)}** (${pct(c, all)})`).join(' | ')} | **${cell(all)}** |`,
  ];
  for (const [k, cs] of rows) {
    const sum = cs.reduce((a, b) => a + b, 0);
    if (sum / clk < 5e-5) continue;
    out.push(`| ${k} | ${cs.filter((_, p) => keep[p]).map(cell).join(' | ')} | ${cell(sum)} (${pct(sum, all)}) |`);
  }
  return out.join('\n');
}

function firmwareBlock(runs, lines) {
  const s = summary(runs.simple);
  const o = summary(runs.ssd1306);
  const clk = s.clk;
  const later = runs.simple.profile['later frames'];
  const perFrame = (c) => c / s.n;
  const out = [];
  out.push(
    `Measured in rp2040js ${runs.version} by \`bash .ci/pico-emu --update\`: the ELFs \`.ci/boards\` builds, ` +
      `${runs.simple.frames.length} frames of each example's main loop (a whole loop of \`circling\`, 100 frames, and ` +
      `its first again, drawn incrementally like the others), clk_sys ${clk / 1e6} MHz as the PLL and CLOCKS ` +
      'registers set it. A frame is one iteration of the main loop, from one frame\'s start to the next\'s, the ' +
      'status line and the wire included: the bytes leave at the rate the SPI or I²C registers set, and the ' +
      'firmware waits for them as on hardware.',
    '',
    table(runs),
    '',
    `\`simple\`'s status line times the frame without the status line drawn after it: ${f1(ms(s.first.cycles, clk))} ms ` +
      `for the first, ${f1(ms(s.timed.min, clk))}–${f1(ms(s.timed.max, clk))} ms for the later ones; the SSD1306's ` +
      'shows the frame before\'s whole iteration. The status lines as read back from the panels: ' +
      `${lines.simple.slice(0, 3).map(code).join(', ')}, …; ${lines.ssd1306.slice(0, 3).map(code).join(', ')}, ….`,
    '',
    NOT_MODELLED,
    '',
    `**Where a later \`simple\` frame's ${f1(ms(s.loop.mean, clk))} ms go.** Every instruction's cycles are ` +
      'charged to the function its address lies in (the ELF\'s symbols), summed by the kind of code and by ' +
      `the part of the frame — before the first window is sent, the windows, the status line — over frames 1–${s.n}:`,
    '',
    matrix(runs.simple, 'simple'),
    '',
    LEGEND,
    '',
    'Before its first window a frame plans: the motion, the camera, `Incremental`\'s old and new ' +
      'silhouettes and the strips to trace (`Region::cut`, `Changes::merge`), the integer kernel\'s per-frame ' +
      'rule (`integer::plan`) — soft `f64` and 64-bit multiplication on a core without an FPU. Its largest functions, and the whole frame\'s:',
    '',
    '| before the first window | ms a frame | | the whole frame | ms a frame |',
    '|---|---:|---|---|---:|',
  );
  const whole = new Map();
  for (const part of later) for (const { fn, cycles } of part.fns) whole.set(fn, (whole.get(fn) || 0) + cycles);
  const a = later[0].fns.slice(0, 12);
  const b = [...whole]
    .map(([fn, cycles]) => ({ fn, cycles }))
    .sort((x, y) => y.cycles - x.cycles)
    .slice(0, 12);
  for (let i = 0; i < Math.max(a.length, b.length); i++) {
    const l = a[i] ? `${code(short(a[i].fn))} | ${ms(perFrame(a[i].cycles), clk).toFixed(2)}` : ' | ';
    const r = b[i] ? `${code(short(b[i].fn))} | ${ms(perFrame(b[i].cycles), clk).toFixed(2)}` : ' | ';
    out.push(`| ${l} | | ${r} |`);
  }
  out.push(
    '',
    `**A later SSD1306 frame's ${f1(ms(o.loop.mean, clk))} ms**, the same way (the flush sends the bounding box of ` +
      `what changed in the driver's buffer; ${f1(ms(o.wire.mean, clk))} ms of it on the wire):`,
    '',
    matrix(runs.ssd1306, 'ssd1306'),
  );
  return out.join('\n');
}

function readmeBlock(runs, board) {
  const r = runs[board];
  const x = summary(r);
  const clk = x.clk;
  const m = (c) => f1(ms(c, clk));
  const later = r.frames.slice(1);
  const mean = (f) => later.reduce((a, g) => a + f(g), 0) / later.length;
  const wire =
    board === 'simple'
      ? `SPI1 at ${f1(r.wire.hz / 1e6)} MHz`
      : `I²C0 at ${f1(r.wire.hz / 1e3)} kHz (an SCL period of ${r.wire.sclPeriodCycles} clk_sys cycles: the controller's HCNT + SPKLEN + 7 high, LCNT + 1 low)`;
  const parts =
    board === 'simple'
      ? [
          ['before the first window (the motion, the camera, the plan, the kernel\'s set-up)', (f) => f.firstByteCycles],
          ['the windows: tracing and sending', (f) => f.cycles - f.firstByteCycles],
          ['the status line', (f) => f.loopCycles - f.cycles],
          ['of the frame, the SPI bytes on the wire', (f) => f.loopWireCycles],
        ]
      : [
          ['drawing into the driver\'s buffer (tracing, dither, status line)', (f) => f.firstByteCycles],
          ['the flush: the changed area over I²C', (f) => f.loopCycles - f.firstByteCycles],
          ['of the frame, the I²C bytes on the wire', (f) => f.loopWireCycles],
        ];
  return [
    `Measured in rp2040js ${runs.version} (\`bash .ci/pico-emu --update\`; docs/firmware.md, "The Pico examples in rp2040js"), ` +
      `clk_sys ${clk / 1e6} MHz, ${wire}, a whole loop of \`circling\`:`,
    '',
    `| | the first frame (whole) | later frames (incremental), 1–${x.n} |`,
    '|---|---|---|',
    `| a frame (the main loop's iteration) | **${m(x.first.loopCycles)} ms, ${fps(x.first.loopCycles, clk)} frames/s** | ` +
      `**${m(x.loop.min)}–${m(x.loop.max)} ms, mean ${m(x.loop.mean)}: ${fps(x.loop.mean, clk)} frames/s** |`,
    ...parts.map(([what, f]) => `| ${what} | ${m(f(x.first))} ms | ${m(mean(f))} ms (mean) |`),
    '',
    NOT_MODELLED,
  ].join('\n');
}

function replaceBlock(path, text) {
  const doc = readFileSync(path, 'utf8');
  const re = /(<!-- pico_emu:begin[^>]*-->\n)[\s\S]*?(<!-- pico_emu:end -->)/;
  if (!re.test(doc)) throw new Error(`${path}: no <!-- pico_emu:begin --> … <!-- pico_emu:end --> block`);
  writeFileSync(path, doc.replace(re, (_, begin, end) => `${begin}${text}\n${end}`));
}

/** Writes the blocks under `root`. */
export function docs(root, runs, lines) {
  runs.version = JSON.parse(readFileSync(new URL('../node_modules/rp2040js/package.json', import.meta.url), 'utf8')).version;
  replaceBlock(join(root, 'docs/firmware.md'), firmwareBlock(runs, lines));
  replaceBlock(join(root, 'boards/rp2040/README.md'), readmeBlock(runs, 'simple'));
  replaceBlock(join(root, 'boards/rp2040-ssd1306/README.md'), readmeBlock(runs, 'ssd1306'));
}
