// The SSD1306 (128×64, I²C) as its write transactions drive it: each transaction's
// first byte is a control byte (D/C# bit 6: commands or GDDRAM data; Co bit 7: one byte
// of that kind, then another control byte), then commands with their parameters or
// data bytes into GDDRAM at the address pointer, which the addressing mode walks
// (horizontal, vertical, page). GDDRAM is 8 pages of 128 columns, a byte a column,
// its bit 0 the page's top row. The picture is the glass seen the usual way up of the
// 128×64 modules: segment remap (A1) and reversed COM scan (C8), the driver's
// unrotated setting, show column 0 at the left and row 0 at the top.

const W = 128;
const H = 64;
const PAGES = H / 8;

// Commands that take parameters: how many.
const PARAMS = {
  0x20: 1, 0x21: 2, 0x22: 2, 0x26: 6, 0x27: 6, 0x29: 5, 0x2a: 5, 0x81: 1, 0x8d: 1,
  0xa3: 2, 0xa8: 1, 0xad: 1, 0xd3: 1, 0xd5: 1, 0xd8: 1, 0xd9: 1, 0xda: 1, 0xdb: 1,
};

export class Ssd1306 {
  constructor(address = 0x3c) {
    this.address = address;
    this.gddram = new Uint8Array(W * PAGES);
    this.written = new Uint8Array(W * PAGES);
    this.mode = 2; // page addressing after reset
    this.colStart = 0;
    this.colEnd = W - 1;
    this.pageStart = 0;
    this.pageEnd = PAGES - 1;
    this.col = 0;
    this.page = 0;
    this.segRemap = false;
    this.comReverse = false;
    this.startLine = 0;
    this.offset = 0;
    this.inverse = false;
    this.allOn = false;
    this.on = false;
    this.cmd = null;
    this.params = [];
    this.control = null;
    this.dataBytes = 0;
  }

  /** A transaction to `address` starts (write): the next byte is a control byte. */
  start() {
    this.control = null;
    this.single = false;
  }

  /** One byte of a write transaction. */
  byte(value) {
    if (this.control === null) {
      this.control = value & 0x40 ? 'data' : 'command';
      this.single = !!(value & 0x80);
      return;
    }
    if (this.control === 'data') this.data(value);
    else this.command(value);
    if (this.single) this.control = null;
  }

  command(value) {
    if (this.cmd !== null) {
      this.params.push(value);
      if (this.params.length === PARAMS[this.cmd]) this.apply(this.cmd, this.params);
      if (this.params.length >= PARAMS[this.cmd]) this.cmd = null;
      return;
    }
    if (PARAMS[value]) {
      this.cmd = value;
      this.params = [];
      return;
    }
    if (value <= 0x0f) this.col = (this.col & 0xf0) | value;
    else if (value <= 0x1f) this.col = (this.col & 0x0f) | ((value & 0x0f) << 4);
    else if (value >= 0x40 && value <= 0x7f) this.startLine = value & 0x3f;
    else if (value === 0xa0 || value === 0xa1) this.segRemap = value === 0xa1;
    else if (value === 0xa4 || value === 0xa5) this.allOn = value === 0xa5;
    else if (value === 0xa6 || value === 0xa7) this.inverse = value === 0xa7;
    else if (value === 0xae || value === 0xaf) this.on = value === 0xaf;
    else if (value >= 0xb0 && value <= 0xb7) this.page = value & 0x07;
    else if (value === 0xc0 || value === 0xc8) this.comReverse = value === 0xc8;
  }

  apply(cmd, p) {
    switch (cmd) {
      case 0x20:
        this.mode = p[0] & 0x03;
        break;
      case 0x21:
        this.colStart = p[0] & 0x7f;
        this.colEnd = p[1] & 0x7f;
        this.col = this.colStart;
        break;
      case 0x22:
        this.pageStart = p[0] & 0x07;
        this.pageEnd = p[1] & 0x07;
        this.page = this.pageStart;
        break;
      case 0xd3:
        this.offset = p[0] & 0x3f;
        break;
      default:
        break;
    }
  }

  // The byte at the pointer, then the pointer moves: horizontal mode along the column
  // range, then to the next page of the page range; vertical mode along the page range,
  // then to the next column; page mode along the row, wrapping within it.
  data(value) {
    const i = this.page * W + this.col;
    this.gddram[i] = value;
    this.written[i] = 1;
    this.dataBytes++;
    if (this.mode === 0) {
      if (this.col < this.colEnd) this.col++;
      else {
        this.col = this.colStart;
        this.page = this.page < this.pageEnd ? this.page + 1 : this.pageStart;
      }
    } else if (this.mode === 1) {
      if (this.page < this.pageEnd) this.page++;
      else {
        this.page = this.pageStart;
        this.col = this.col < this.colEnd ? this.col + 1 : this.colStart;
      }
    } else {
      this.col = this.col < W - 1 ? this.col + 1 : 0;
    }
  }

  /** The glass: 128 × 64 bytes, 1 lit, 0 dark, row-major; `null` while a byte of
   * GDDRAM the glass shows was never written or the display is off. */
  picture() {
    if (!this.on) return null;
    const out = new Uint8Array(W * H);
    for (let y = 0; y < H; y++) {
      // The glass row y is driven by COM (63 - y) with the modules' glass; the COM
      // scan and the offset say which GDDRAM row that COM shows.
      const com = H - 1 - y;
      const scan = this.comReverse ? H - 1 - com : com;
      const row = (scan + this.startLine + this.offset) % H;
      for (let x = 0; x < W; x++) {
        const seg = W - 1 - x;
        const col = this.segRemap ? W - 1 - seg : seg;
        const i = (row >> 3) * W + col;
        if (!this.written[i]) return null;
        let lit = (this.gddram[i] >> (row & 7)) & 1;
        if (this.inverse) lit ^= 1;
        if (this.allOn) lit = 1;
        out[y * W + x] = lit;
      }
    }
    return out;
  }
}
