// An ELF32 (little-endian, ARM) firmware: its load segments and its function symbols.

/** The segments to load: `{ address, bytes }` at each PT_LOAD's physical address (the
 * flash image the linker laid out; RAM sections are copied from it by the firmware). */
export function loadSegments(elf) {
  const v = new DataView(elf.buffer, elf.byteOffset, elf.byteLength);
  if (v.getUint32(0, false) !== 0x7f454c46 || elf[4] !== 1 || elf[5] !== 1) {
    throw new Error('not a 32-bit little-endian ELF');
  }
  const phoff = v.getUint32(0x1c, true);
  const phentsize = v.getUint16(0x2a, true);
  const phnum = v.getUint16(0x2c, true);
  const segments = [];
  for (let i = 0; i < phnum; i++) {
    const p = phoff + i * phentsize;
    const type = v.getUint32(p, true);
    const offset = v.getUint32(p + 4, true);
    const paddr = v.getUint32(p + 12, true);
    const filesz = v.getUint32(p + 16, true);
    if (type === 1 && filesz > 0) {
      segments.push({ address: paddr, bytes: elf.subarray(offset, offset + filesz) });
    }
  }
  return segments;
}

/** The function symbols (`STT_FUNC`, size > 0), sorted by address: `{ start, end, name }`
 * with the Thumb bit cleared and the Rust name demangled. */
export function functions(elf) {
  const v = new DataView(elf.buffer, elf.byteOffset, elf.byteLength);
  const shoff = v.getUint32(0x20, true);
  const shentsize = v.getUint16(0x2e, true);
  const shnum = v.getUint16(0x30, true);
  const section = (i) => {
    const s = shoff + i * shentsize;
    return {
      type: v.getUint32(s + 4, true),
      offset: v.getUint32(s + 16, true),
      size: v.getUint32(s + 20, true),
      link: v.getUint32(s + 24, true),
    };
  };
  const out = new Map();
  for (let i = 0; i < shnum; i++) {
    const sym = section(i);
    if (sym.type !== 2) continue; // SHT_SYMTAB
    const str = section(sym.link);
    for (let e = sym.offset; e + 16 <= sym.offset + sym.size; e += 16) {
      const info = elf[e + 12];
      const size = v.getUint32(e + 8, true);
      if ((info & 0xf) !== 2 || size === 0) continue; // STT_FUNC
      const start = v.getUint32(e + 4, true) & ~1;
      let n = str.offset + v.getUint32(e, true);
      let end = n;
      while (elf[end] !== 0) end++;
      const raw = Buffer.from(elf.subarray(n, end)).toString('latin1');
      // Aliases (one body, several names) keep the first name seen.
      if (!out.has(start)) out.set(start, { start, end: start + size, name: demangle(raw) });
    }
  }
  return [...out.values()].sort((a, b) => a.start - b.start);
}

const LEGACY_ESCAPES = {
  SP: '@', BP: '*', RF: '&', LT: '<', GT: '>', LP: '(', RP: ')', C: ',',
};

/** A Rust symbol's path: legacy (`_ZN…E`, the hash dropped) or v0 (`_R`, simple paths
 * only); any other name as it is. */
export function demangle(mangled) {
  const name = mangled.replace(/\.llvm\.\d+$/, '');
  if (name.startsWith('_ZN') && name.endsWith('E')) {
    const parts = [];
    let i = 3;
    while (i < name.length - 1) {
      const m = /^\d+/.exec(name.slice(i));
      if (!m) return name;
      i += m[0].length;
      const len = Number(m[0]);
      parts.push(name.slice(i, i + len));
      i += len;
    }
    if (parts.length > 1 && /^h[0-9a-f]{16}$/.test(parts[parts.length - 1])) parts.pop();
    return parts
      .map((p) =>
        p
          .replace(/^_\$/, '$')
          .replace(/\$(SP|BP|RF|LT|GT|LP|RP|C)\$/g, (_, k) => LEGACY_ESCAPES[k])
          .replace(/\$u([0-9a-f]{2})\$/g, (_, h) => String.fromCharCode(parseInt(h, 16)))
          .replace(/\.\./g, '::'),
      )
      .join('::');
  }
  if (name.startsWith('_R')) {
    const path = v0Path(name, 2);
    return path && path.end === name.length ? path.text : v0Idents(name);
  }
  return name;
}

// A v0 name this parser does not follow (impls, generics): its identifiers in order,
// the disambiguators and back-references skipped; a label, not a path.
function v0Idents(s) {
  const out = [];
  let i = 2;
  while (i < s.length) {
    const c = s[i];
    if ('CMXY'.includes(c) && s[i + 1] === 's') {
      i = skipDisambiguator(s, i + 1);
    } else if (c === 'B') {
      const e = s.indexOf('_', i);
      i = e < 0 ? s.length : e + 1;
    } else if (c === 'N') {
      i += 2;
    } else if (c >= '0' && c <= '9') {
      const id = v0Ident(s, i);
      out.push(id.text);
      i = id.end;
    } else {
      i++;
    }
  }
  return out.join('::');
}

// v0: `N <namespace> <path> <ident>` and `C [s<base62>_] <ident>`; others give up.
function v0Path(s, i) {
  const c = s[i];
  if (c === 'C') {
    i = skipDisambiguator(s, i + 1);
    const id = v0Ident(s, i);
    return id && { text: id.text, end: id.end };
  }
  if (c === 'N') {
    const inner = v0Path(s, i + 2);
    if (!inner) return null;
    const j = skipDisambiguator(s, inner.end);
    const id = v0Ident(s, j);
    if (!id) return null;
    return { text: id.text ? `${inner.text}::${id.text}` : inner.text, end: id.end };
  }
  return null;
}

function skipDisambiguator(s, i) {
  if (s[i] !== 's') return i;
  const e = s.indexOf('_', i);
  return e < 0 ? i : e + 1;
}

function v0Ident(s, i) {
  const m = /^(\d+)_?/.exec(s.slice(i));
  if (!m) return null;
  const len = Number(m[1]);
  const start = i + m[0].length;
  return { text: s.slice(start, start + len), end: start + len };
}
