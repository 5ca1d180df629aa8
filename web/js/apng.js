// Animated PNG, written in the browser: the frames of a "Save animation" as
// one file that any browser plays and any slide program shows (its first
// frame is the plain PNG image, so a program that knows only PNG shows that).
// Each frame is RGB with every row filtered by "Sub", compressed with the
// browser's own zlib (CompressionStream 'deflate'): no library, no build step.
// The layout follows the APNG specification: IHDR, acTL, then per frame an
// fcTL, and its data in IDAT (the first frame) or fdAT (the others), IEND.

const SIGNATURE = [137, 80, 78, 71, 13, 10, 26, 10];

let crcTable = null;
function crc32(bytes) {
  if (!crcTable) {
    crcTable = new Uint32Array(256);
    for (let n = 0; n < 256; n++) {
      let c = n;
      for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
      crcTable[n] = c >>> 0;
    }
  }
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

/** A chunk: length, type, data, CRC of type and data. */
function chunk(type, data) {
  const out = new Uint8Array(12 + data.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, data.length);
  for (let i = 0; i < 4; i++) out[4 + i] = type.charCodeAt(i);
  out.set(data, 8);
  view.setUint32(8 + data.length, crc32(out.subarray(4, 8 + data.length)));
  return out;
}

/** Big-endian fields: [[value, bytes], …]. */
function fields(list) {
  const size = list.reduce((a, [, n]) => a + n, 0);
  const out = new Uint8Array(size);
  const view = new DataView(out.buffer);
  let at = 0;
  for (const [v, n] of list) {
    if (n === 4) view.setUint32(at, v);
    else if (n === 2) view.setUint16(at, v);
    else view.setUint8(at, v);
    at += n;
  }
  return out;
}

async function deflate(bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new CompressionStream('deflate'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/** RGBA pixels as PNG scanlines of RGB, each row filtered by Sub (type 1). */
function scanlines(rgba, width, height) {
  const stride = width * 3 + 1;
  const out = new Uint8Array(stride * height);
  for (let y = 0; y < height; y++) {
    const row = y * stride;
    out[row] = 1;
    let src = y * width * 4;
    for (let x = 0; x < width; x++, src += 4) {
      const at = row + 1 + x * 3;
      for (let c = 0; c < 3; c++) {
        const left = x > 0 ? rgba[src - 4 + c] : 0;
        out[at + c] = (rgba[src + c] - left) & 0xff;
      }
    }
  }
  return out;
}

/**
 * Writes an APNG of `count` frames of `width` × `height`, each shown
 * `delayMs`, looping forever: `add` each frame's RGBA pixels in turn (each
 * is compressed at once, so only the compressed frames are kept), then
 * `blob()`.
 */
export class ApngWriter {
  constructor(width, height, count, delayMs) {
    this.width = width;
    this.height = height;
    this.count = count;
    this.delay = Math.round(delayMs);
    this.sequence = 0;
    this.frames = 0;
    this.parts = [
      new Uint8Array(SIGNATURE),
      chunk('IHDR', fields([[width, 4], [height, 4], [8, 1], [2, 1], [0, 1], [0, 1], [0, 1]])),
      chunk('acTL', fields([[count, 4], [0, 4]])),
    ];
  }

  /** Adds the next frame (RGBA, `width` × `height`). */
  async add(rgba) {
    if (this.frames >= this.count) throw new Error(`the animation has ${this.count} frames`);
    if (rgba.length !== this.width * this.height * 4) throw new Error('the frames of an animation have one size');
    const { width, height } = this;
    this.parts.push(chunk('fcTL', fields([[this.sequence++, 4], [width, 4], [height, 4], [0, 4], [0, 4], [this.delay, 2], [1000, 2], [0, 1], [0, 1]])));
    const data = await deflate(scanlines(rgba, width, height));
    if (this.frames === 0) {
      this.parts.push(chunk('IDAT', data));
    } else {
      const fd = new Uint8Array(4 + data.length);
      new DataView(fd.buffer).setUint32(0, this.sequence++);
      fd.set(data, 4);
      this.parts.push(chunk('fdAT', fd));
    }
    this.frames += 1;
  }

  /** The file, once every frame was added. */
  blob() {
    if (this.frames !== this.count) throw new Error(`the animation has ${this.frames} of its ${this.count} frames`);
    return new Blob([...this.parts, chunk('IEND', new Uint8Array(0))], { type: 'image/apng' });
  }
}
