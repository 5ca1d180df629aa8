// The JavaScript side of shadelab's WebAssembly API (crates/shadelab-wasm,
// src/abi.rs): one request per export, bytes exchanged through buffers that
// the module owns. Works in a worker, on the page and in Node.

const encoder = new TextEncoder();
const decoder = new TextDecoder();

/** A request the engine refused; `message` is the text to show the user. */
export class ShadelabError extends Error {}

/** One instance of the engine: its own memory, model and frame. */
export class Shadelab {
  /** Instantiates a compiled `WebAssembly.Module`. */
  static async create(module) {
    const instance = await WebAssembly.instantiate(module, {});
    return new Shadelab(instance.exports);
  }

  constructor(exports) {
    this.x = exports;
  }

  /** The built-in models: [{name, description, detail_meaning, default_detail, detail_min, detail_max, default_crease}]. */
  models() {
    return this.#call(this.x.shadelab_models());
  }

  /** Loads the user's mesh file (format by the extension of `name`); returns its summary. */
  loadFile(name, bytes) {
    const nameBytes = encoder.encode(name);
    this.#input(nameBytes.length + bytes.byteLength, (view) => {
      view.set(nameBytes, 0);
      view.set(new Uint8Array(bytes), nameBytes.length);
    });
    return this.#call(this.x.shadelab_load_file(nameBytes.length));
  }

  /**
   * The loaded file's mesh as bytes (a Uint8Array of its own) for another
   * engine's `adoptFile`: the file is parsed once, by one engine.
   */
  shareFile() {
    this.#call(this.x.shadelab_share_file());
    const start = this.x.shadelab_output();
    return new Uint8Array(this.x.memory.buffer.slice(start, start + this.x.shadelab_output_len()));
  }

  /** Takes the mesh another engine's `shareFile` gave as file `name`; returns its summary. */
  adoptFile(name, bytes) {
    const nameBytes = encoder.encode(name);
    this.#input(nameBytes.length + bytes.byteLength, (view) => {
      view.set(nameBytes, 0);
      view.set(new Uint8Array(bytes.buffer ?? bytes, bytes.byteOffset ?? 0, bytes.byteLength), nameBytes.length);
    });
    return this.#call(this.x.shadelab_adopt_file(nameBytes.length));
  }

  /** How often this engine parsed files, adopted meshes, prepared models, read scenes and drew frames. */
  counts() {
    return this.#call(this.x.shadelab_counts());
  }

  /**
   * Renders a scene given as TOML text. Returns {width, height, rasterizer,
   * stats, cost, view, pixels, ms}: `pixels` a Uint8ClampedArray copy of the
   * RGBA frame, `ms` the time the engine's call took (reading the scene and
   * drawing it), without copying the pixels out or anything before or after.
   * `spare`, an ArrayBuffer of an earlier frame of this size, is reused for
   * the pixels instead of a new one.
   */
  render(sceneToml, spare = null) {
    const text = encoder.encode(sceneToml);
    this.#input(text.length, (view) => view.set(text));
    const start = performance.now();
    const status = this.x.shadelab_render();
    const ms = performance.now() - start;
    const info = this.#call(status);
    info.ms = ms;
    info.pixels = this.pixels(spare);
    return info;
  }

  /**
   * Renders a scene given as TOML text with the three methods at once, flat,
   * Gouraud and Phong, over one pass of the geometry: what three `render`s
   * of the three panels' texts (which differ only in `render.shading`) give.
   * Returns {frames: [flat, gouraud, phong], ms}, each frame as `render`'s
   * but without `ms` (`ms` is the call's, the three together); `spares`,
   * up to three ArrayBuffers of earlier frames of this size, are reused for
   * the pixels. The text's own method's frame becomes the last frame.
   *
   * With `part` = [k, n], only part k of n of the frames' rows is drawn
   * (`shadelab_render_methods_part`): the answer's `rows` = [first, end]
   * says which, each frame's `pixels` hold those rows, and its counts are
   * the frame's but for its rows' pixels (`stats.fragments_shaded`,
   * `stats.covered_pixels`, `cost.per_pixel`) and for flat's evaluations
   * (`cost.per_polygon`: those of the polygons whose top row the part holds),
   * both in `stats.lighting_evaluations` too, which the parts add up to (see
   * `joinParts`). No last frame is kept.
   */
  renderMethods(sceneToml, spares = [], part = null) {
    const text = encoder.encode(sceneToml);
    this.#input(text.length, (view) => view.set(text));
    const start = performance.now();
    const status = part ? this.x.shadelab_render_methods_part(part[0], part[1]) : this.x.shadelab_render_methods();
    const ms = performance.now() - start;
    const { frames, rows } = this.#call(status);
    frames.forEach((frame, k) => {
      frame.pixels = this.#copy(this.x.shadelab_image(k), this.x.shadelab_image_len(k), spares[k]);
    });
    return { frames, ms, rows: rows ?? [0, frames[0].height] };
  }

  /** A copy of `length` bytes at `start` of the memory, in `spare` when it is an ArrayBuffer of that size. */
  #copy(start, length, spare = null) {
    if (spare && spare.byteLength === length) {
      const out = new Uint8ClampedArray(spare);
      out.set(new Uint8ClampedArray(this.x.memory.buffer, start, length));
      return out;
    }
    return new Uint8ClampedArray(this.x.memory.buffer.slice(start, start + length));
  }

  /**
   * A copy of the last frame's RGBA pixels (as drawn, overlays included),
   * in `spare` when it is an ArrayBuffer of their size.
   */
  pixels(spare = null) {
    return this.#copy(this.x.shadelab_pixels(), this.x.shadelab_pixels_len(), spare);
  }

  /** Draws overlays ('wireframe,light', …) over the last frame; returns its pixels. */
  overlays(list) {
    this.#json('overlays', { overlays: list });
    return this.pixels();
  }

  /** The last frame's error map: {mean, max, max_at, …, scale, images: {heat, exact?, bar?}}. */
  errors(request) {
    return this.#json('errors', request);
  }

  /** The last error map on another scale: {scale, images: {heat}}. */
  heat(request) {
    return this.#json('heat', request);
  }

  /** The pixel inspector: {x, y, header, methods: [{method, text, color, …}]}. */
  inspect(request) {
    return this.#json('inspect', request);
  }

  /** A scanline profile: {pixels, curves: [{kind, values, derivative, edges, polygon_edges}]}. */
  profile(request) {
    return this.#json('profile', request);
  }

  /** The quad study: {angle, whole_centre, fans_centre, curve, images: {whole, fans}}. */
  quad(request) {
    return this.#json('quad', request);
  }

  /** The instruments' texts in one language: {id: text}. */
  texts(lang) {
    return this.#json('texts', { lang });
  }

  /**
   * Sends `request` as JSON to export `shadelab_<name>`; an answer listing
   * `images` gets them as {name: {width, height, pixels}} instead.
   */
  #json(name, request) {
    const text = encoder.encode(JSON.stringify(request));
    this.#input(text.length, (view) => view.set(text));
    const answer = this.#call(this.x[`shadelab_${name}`]());
    if (answer && Array.isArray(answer.images)) {
      const images = {};
      answer.images.forEach((info, k) => {
        const start = this.x.shadelab_image(k);
        const length = this.x.shadelab_image_len(k);
        images[info.name] = {
          width: info.width,
          height: info.height,
          pixels: new Uint8ClampedArray(this.x.memory.buffer.slice(start, start + length)),
        };
      });
      answer.images = images;
    }
    return answer;
  }

  #input(length, fill) {
    const start = this.x.shadelab_input(length);
    fill(new Uint8Array(this.x.memory.buffer, start, length));
  }

  #call(status) {
    const start = this.x.shadelab_result();
    const length = this.x.shadelab_result_len();
    const answer = JSON.parse(decoder.decode(new Uint8Array(this.x.memory.buffer, start, length)));
    if (status !== 0) {
      throw new ShadelabError(answer.error);
    }
    return answer;
  }
}

/**
 * One frame from its parts (`renderMethods` with `part`), each `{frame,
 * rows}` with `frame` one method's part: the rows one under the other, in
 * `spare` when it is an ArrayBuffer of the frame's size, and the parts'
 * pixel counts and flat's evaluations added up. A part drawn whole (rows from 0 to the height: a
 * mode of the scanline rasterizer) is the frame.
 */
export function joinParts(parts, spare = null) {
  const drawn = parts.filter(({ rows }) => rows[1] > rows[0]);
  const whole = drawn.find(({ frame, rows }) => rows[0] === 0 && rows[1] === frame.height);
  if (whole) return whole.frame;
  const first = drawn[0].frame;
  const length = first.width * first.height * 4;
  const pixels = spare && spare.byteLength === length ? new Uint8ClampedArray(spare) : new Uint8ClampedArray(length);
  const sum = (read) => drawn.reduce((total, { frame }) => total + read(frame), 0);
  for (const { frame, rows } of drawn) pixels.set(frame.pixels, rows[0] * first.width * 4);
  const perPixel = sum((f) => f.cost.per_pixel);
  const perPolygon = sum((f) => f.cost.per_polygon);
  return {
    ...first,
    pixels,
    stats: {
      ...first.stats,
      fragments_shaded: sum((f) => f.stats.fragments_shaded),
      covered_pixels: sum((f) => f.stats.covered_pixels),
      lighting_evaluations: perPolygon + first.cost.per_vertex + perPixel,
    },
    cost: { ...first.cost, per_polygon: perPolygon, per_pixel: perPixel },
  };
}
