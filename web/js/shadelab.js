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
   * Renders a scene given as TOML text. Returns {width, height, stats,
   * pixels}, `pixels` a Uint8ClampedArray copy of the RGBA frame.
   */
  render(sceneToml) {
    const text = encoder.encode(sceneToml);
    this.#input(text.length, (view) => view.set(text));
    const info = this.#call(this.x.shadelab_render());
    const start = this.x.shadelab_pixels();
    const length = this.x.shadelab_pixels_len();
    info.pixels = new Uint8ClampedArray(this.x.memory.buffer.slice(start, start + length));
    return info;
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
