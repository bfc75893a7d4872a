// The RP2040 of rp2040js with the firmware's ELF in flash, booted the way a Pico boots
// from flash but without the boot ROM, run by its own loop that counts the core's
// cycles, and the wire time of SPI and I²C charged at the rates their registers set.

import { RP2040, ConsoleLogger, LogLevel } from 'rp2040js';
import { functions, loadSegments } from './elf.mjs';

const FLASH = 0x10000000;
const TIMER_BASE = 0x40054;
const TIMERAWL = 0x28;
const TIMELR = 0x0c;

/** Warnings of rp2040js (its logger and its SIO's console.warn), counted and shown once
 * each: the firmware polls registers rp2040js does not model, and each access warns. */
export class Warnings {
  constructor() {
    this.counts = new Map();
  }

  note(text) {
    // The access's address and value vary; the kind of message is what is counted.
    const kind = text.replace(/0x[0-9a-f]+|\b[0-9a-f]{5,}\b/gi, '…');
    const n = (this.counts.get(kind) || 0) + 1;
    this.counts.set(kind, n);
    if (n === 1) process.stderr.write(`rp2040js: ${text} (shown once; counted)\n`);
  }

  summary() {
    return [...this.counts].map(([kind, n]) => `${n} × ${kind}`);
  }
}

export class Pico {
  /**
   * @param {Uint8Array} elf the firmware
   * @param {Warnings} warnings where rp2040js's warnings go
   */
  constructor(elf, warnings) {
    const mcu = new RP2040();
    this.mcu = mcu;
    const logger = new ConsoleLogger(LogLevel.Warn, true);
    logger.warn = (component, message) => warnings.note(`${component}: ${message}`);
    logger.error = (component, message) => {
      throw new Error(`rp2040js: ${component}: ${message}`);
    };
    logger.info = () => {};
    logger.debug = () => {};
    // The core and every peripheral log through the chip's logger.
    mcu.logger = logger;
    // The SIO warns through console.warn directly.
    console.warn = (...args) => warnings.note(args.join(' '));

    // The boot ROM stays empty (zeros): the core starts at the second-stage bootloader
    // at the start of flash with the stack at the top of SRAM, as the ROM would leave
    // it; boot2 sets up the flash interface, then VTOR, the stack and the reset handler
    // from the firmware's vector table.
    for (const { address, bytes } of loadSegments(elf)) {
      if (address < FLASH || address + bytes.length > FLASH + mcu.flash.length) {
        throw new Error(`a load segment at 0x${address.toString(16)} is outside flash`);
      }
      mcu.flash.set(bytes, address - FLASH);
    }
    mcu.core.SP = 0x20042000;
    mcu.core.PC = 0x10000000;

    this.cycles = 0;
    this.instructions = 0;
    /** The wire time charged so far, in core cycles. */
    this.wireCycles = 0;
    this.nanosPerCycle = 1e9 / mcu.clkSys;
    mcu.addClockListener((hz) => {
      this.nanosPerCycle = 1e9 / hz;
    });

    // The function of every flash halfword, for the profile: index into `this.fns`,
    // the last index for code outside every function (boot2, RAM, ROM).
    this.fns = functions(elf);
    const textEnd = this.fns.reduce((e, f) => Math.max(e, f.end), FLASH);
    this.other = this.fns.length;
    this.fnAt = new Uint16Array((textEnd - FLASH) >> 1).fill(this.other);
    this.fns.forEach((f, i) => this.fnAt.fill(i, (f.start - FLASH) >> 1, (f.end - FLASH) >> 1));
    /** Cycles by (bucket, function): `profile[bucket * (fns + 1) + fn]`; the bucket is
     * the caller's (`this.bucket`). */
    this.buckets = 8;
    this.bucket = 0;
    this.profile = new Float64Array(this.buckets * (this.fns.length + 1));
    /** Cycles and executions by flash halfword for one bucket (`pcBucket`), when
     * `pcProfile()` asked: where inside a function the time goes. */
    this.pcCycles = null;
    this.pcCount = null;
    this.pcBucket = -1;

    /** Called at each read of the timer's low word: (cycles, microseconds read). */
    this.onTimerRead = () => {};
    const timer = mcu.peripherals[TIMER_BASE];
    const read = timer.readUint32.bind(timer);
    timer.readUint32 = (offset) => {
      const value = read(offset);
      if (offset === TIMERAWL || offset === TIMELR) this.onTimerRead(this.cycles, value);
      return value;
    };
  }

  /** The clock the cores run at (from the PLL and CLOCKS registers). */
  get clkSys() {
    return this.mcu.clkSys;
  }

  /** An alarm `cycles` core cycles from now (fractions allowed) calling `fn`. */
  after(alarm, cycles) {
    alarm.schedule(cycles * this.nanosPerCycle);
  }

  /** SPI `index`'s bytes to `onByte(value)` as each starts on the wire, each taking its
   * wire time (its data bits at the SPI clock the registers set: clk_peri / (CPSDVSR ×
   * (1 + SCR))) before the next can start, so the core waits as on hardware. */
  spi(index, onByte) {
    const spi = this.mcu.spi[index];
    const done = this.mcu.clock.createAlarm(() => spi.completeTransmit(0));
    spi.onTransmit = (value) => {
      onByte(value);
      const hz = spi.clockFrequency;
      if (!hz) throw new Error(`SPI${index}: transmit with no clock set`);
      const ns = (spi.dataBits * 1e9) / hz;
      this.wireCycles += ns / this.nanosPerCycle;
      done.schedule(ns);
    };
    return spi;
  }

  /** I²C `index` as a controller writing to one target at `address`: `device.start()`
   * at each addressed write, `device.byte(value)` for each data byte; START and STOP take
   * one SCL period each, the address and every byte nine (eight bits and the ACK). The
   * SCL period is the DesignWare controller's from its registers, in clk_sys cycles:
   * (HCNT + SPKLEN + 7) high and (LCNT + 1) low. Reads are not modelled. */
  i2c(index, address, device) {
    const i2c = this.mcu.i2c[index];
    const clock = this.mcu.clock;
    // IC_FS_SPKLEN as written (rp2040js keeps a written value only if its bit 0 is clear).
    let spikelen = 7;
    const write = i2c.writeUint32.bind(i2c);
    i2c.writeUint32 = (offset, value) => {
      if (offset === 0xa0) spikelen = value & 0xff;
      write(offset, value);
    };
    const period = () => i2c.sclHighPeriod + spikelen + 7 + (i2c.sclLowPeriod + 1);
    let next = null;
    const alarm = clock.createAlarm(() => next());
    const wait = (bits, then) => {
      next = then;
      this.wireCycles += bits * period();
      this.after(alarm, bits * period());
    };
    i2c.onStart = () => wait(1, () => i2c.completeStart());
    i2c.onConnect = (addr, mode) => {
      const ack = addr === address && mode === 0;
      if (ack) device.start();
      wait(9, () => i2c.completeConnect(ack));
    };
    i2c.onWriteByte = (value) => {
      device.byte(value);
      wait(9, () => i2c.completeWrite(true));
    };
    i2c.onReadByte = () => {
      throw new Error(`I2C${index}: a read (not modelled)`);
    };
    i2c.onStop = () => wait(1, () => i2c.completeStop());
    this.i2cPeriod = period;
    return i2c;
  }

  /** Counts the cycles and executions of bucket `bucket` by instruction address too
   * (`pcCycles`, `pcCount`). */
  pcProfile(bucket) {
    this.pcBucket = bucket;
    this.pcCycles = new Float64Array(this.fnAt.length);
    this.pcCount = new Float64Array(this.fnAt.length);
    /** Calls in that bucket: "callee caller" (indices into `fns`) → count. */
    this.calls = new Map();
  }

  /** Runs until `done()` (checked every instruction) or `limit` cycles pass. */
  run(done, limit) {
    const { mcu, fnAt, profile } = this;
    const { core, clock } = mcu;
    const stride = this.fns.length + 1;
    const textEnd = FLASH + fnAt.length * 2;
    const other = this.other;
    const end = this.cycles + limit;
    while (!done()) {
      if (this.cycles > end) throw new Error(`no result within ${limit} cycles`);
      if (core.waiting) {
        const ns = clock.nanosToNextAlarm;
        if (!ns) throw new Error('the core waits for an interrupt that nothing will raise');
        clock.tick(ns);
        this.cycles += ns / this.nanosPerCycle;
        continue;
      }
      const pc = core.PC;
      const cycles = core.executeInstruction();
      this.cycles += cycles;
      this.instructions++;
      const fn = pc >= FLASH && pc < textEnd ? fnAt[(pc - FLASH) >> 1] : other;
      profile[this.bucket * stride + fn] += cycles;
      if (this.bucket === this.pcBucket && fn !== other) {
        this.pcCycles[(pc - FLASH) >> 1] += cycles;
        this.pcCount[(pc - FLASH) >> 1]++;
        // A call: the function's first instruction, the caller from the link register.
        if (pc === this.fns[fn].start) {
          const lr = (core.LR & ~1) - 2;
          const from = lr >= FLASH && lr < textEnd ? fnAt[(lr - FLASH) >> 1] : other;
          const key = `${fn} ${from}`;
          this.calls.set(key, (this.calls.get(key) || 0) + 1);
        }
      }
      clock.tick(cycles * this.nanosPerCycle);
    }
  }
}
