// The ST7789 controller as the SPI byte stream drives it: a command byte (DC low),
// then its parameters or pixel data (DC high); the column/row window (CASET, RASET),
// the memory write (RAMWR and RAMWRC: the write pointer walks the window row by row),
// the address order (MADCTL) and the pixel format (COLMOD, 16 bits a pixel only). The
// controller memory is 240 columns × 320 rows of RGB565; a 240×240 panel shows its
// first 240 rows.

const CASET = 0x2a;
const RASET = 0x2b;
const RAMWR = 0x2c;
const RAMWRC = 0x3c;
const MADCTL = 0x36;
const COLMOD = 0x3a;
const INVOFF = 0x20;
const INVON = 0x21;
const DISPOFF = 0x28;
const DISPON = 0x29;
const SWRESET = 0x01;

const GRAM_W = 240;
const GRAM_H = 320;

export class St7789 {
  constructor(width = 240, height = 240) {
    this.width = width;
    this.height = height;
    this.gram = new Uint16Array(GRAM_W * GRAM_H);
    // Which pixels were ever written: a picture with an unwritten pixel is incomplete.
    this.written = new Uint8Array(GRAM_W * GRAM_H);
    this.reset();
    /** Pixels written, and memory writes started (RAMWR), since reset. */
    this.pixels = 0;
    this.windows = 0;
    /** Called with the command byte of every command. */
    this.onCommand = () => {};
  }

  reset() {
    this.cmd = null;
    this.params = [];
    this.xs = 0;
    this.xe = GRAM_W - 1;
    this.ys = 0;
    this.ye = GRAM_H - 1;
    this.madctl = 0;
    this.colmod = 0x66;
    this.inverted = false;
    this.on = false;
    this.half = null;
  }

  /** One byte on the wire: `dc` high for data. */
  byte(value, dc) {
    if (!dc) {
      this.command(value);
      return;
    }
    if (this.cmd === RAMWR || this.cmd === RAMWRC) {
      this.pixelByte(value);
      return;
    }
    if (this.cmd === null) return;
    this.params.push(value);
    const p = this.params;
    switch (this.cmd) {
      case CASET:
        if (p.length === 4) [this.xs, this.xe] = [(p[0] << 8) | p[1], (p[2] << 8) | p[3]];
        break;
      case RASET:
        if (p.length === 4) [this.ys, this.ye] = [(p[0] << 8) | p[1], (p[2] << 8) | p[3]];
        break;
      case MADCTL:
        if (p.length === 1) this.madctl = value;
        break;
      case COLMOD:
        if (p.length === 1) this.colmod = value;
        break;
      default:
        break;
    }
  }

  command(value) {
    this.cmd = value;
    this.params = [];
    this.half = null;
    this.onCommand(value);
    switch (value) {
      case SWRESET:
        this.reset();
        this.cmd = value;
        break;
      case RAMWR:
        if ((this.colmod & 0x07) !== 0x05) {
          throw new Error(`ST7789: RAMWR with COLMOD 0x${this.colmod.toString(16)} (only 16 bits a pixel is modelled)`);
        }
        this.windows++;
        this.cx = this.xs;
        this.cy = this.ys;
        break;
      case INVON:
        this.inverted = true;
        break;
      case INVOFF:
        this.inverted = false;
        break;
      case DISPON:
        this.on = true;
        break;
      case DISPOFF:
        this.on = false;
        break;
      default:
        break;
    }
  }

  // Two bytes a pixel, the high byte first; the pointer walks the window's columns,
  // then its rows, and wraps to the window's start.
  pixelByte(value) {
    if (this.half === null) {
      this.half = value;
      return;
    }
    const rgb = (this.half << 8) | value;
    this.half = null;
    this.put(this.cx, this.cy, rgb);
    this.pixels++;
    if (this.cx < this.xe) {
      this.cx++;
    } else {
      this.cx = this.xs;
      this.cy = this.cy < this.ye ? this.cy + 1 : this.ys;
    }
  }

  // MADCTL: MY (0x80) mirrors the row address, MX (0x40) the column address, MV (0x20)
  // exchanges them; the mirrors act on the addresses the host sends, before the exchange.
  put(c, r, rgb) {
    const mv = this.madctl & 0x20;
    const cols = mv ? GRAM_H : GRAM_W;
    const rows = mv ? GRAM_W : GRAM_H;
    if (c >= cols || r >= rows) return;
    if (this.madctl & 0x40) c = cols - 1 - c;
    if (this.madctl & 0x80) r = rows - 1 - r;
    const [x, y] = mv ? [r, c] : [c, r];
    const i = y * GRAM_W + x;
    this.gram[i] = rgb;
    this.written[i] = 1;
  }

  /** The panel's picture: its `width` × `height` pixels of the controller memory,
   * RGB565, row-major; `null` where a pixel was never written. */
  picture() {
    const out = new Uint16Array(this.width * this.height);
    for (let y = 0; y < this.height; y++) {
      for (let x = 0; x < this.width; x++) {
        const i = y * GRAM_W + x;
        if (!this.written[i]) return null;
        out[y * this.width + x] = this.gram[i];
      }
    }
    return out;
  }
}
