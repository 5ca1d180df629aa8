// The three panels: each a canvas drawn by its own worker. A panel renders
// the newest scene it was given: while a frame is being drawn, later scenes
// replace each other and only the last is drawn next, so dragging never
// queues up stale frames.
import { t, formatCount } from './i18n.js';

/** How many recent frame times each panel keeps (for the page and its tests). */
const HISTORY = 240;

export class Panel {
  constructor(method, figure, module) {
    this.method = method;
    this.figure = figure;
    this.canvas = figure.querySelector('canvas');
    // Frames arrive as pixels, and instruments read pixels back: keep the canvas in memory.
    this.context = this.canvas.getContext('2d', { willReadFrequently: true });
    this.timeEl = figure.querySelector('.time');
    this.statsEl = figure.querySelector('.stats');
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    this.nextId = 1;
    this.waiting = new Map();
    this.busy = false;
    this.pending = null;
    this.times = [];
    this.frames = 0;
    this.lastStats = null;
    this.onframe = () => {};
    this.onerror = () => {};
    this.worker.onmessage = (event) => this.#receive(event.data);
    this.ready = this.#request({ type: 'init', module });
  }

  #request(msg, transfer = []) {
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.waiting.set(id, { resolve, reject });
      this.worker.postMessage({ ...msg, id }, transfer);
    });
  }

  #receive(msg) {
    const waiter = this.waiting.get(msg.id);
    this.waiting.delete(msg.id);
    if (!waiter) return;
    if (msg.type === 'error') {
      const error = new Error(msg.message);
      error.crashed = msg.crashed;
      waiter.reject(error);
    } else {
      waiter.resolve(msg);
    }
  }

  /** Loads the user's file into this panel's engine; resolves to its summary. */
  async loadFile(name, bytes) {
    const answer = await this.#request({ type: 'load-file', name, bytes });
    return answer.summary;
  }

  /** Asks for a frame of `scene` (TOML); the newest request wins. */
  render(scene) {
    this.pending = scene;
    if (!this.busy) this.#next();
  }

  /** Resolves once no frame is being drawn or waiting. */
  idle() {
    if (!this.busy && this.pending === null) return Promise.resolve();
    return new Promise((resolve) => {
      const check = () => (!this.busy && this.pending === null ? resolve() : setTimeout(check, 5));
      check();
    });
  }

  async #next() {
    const scene = this.pending;
    this.pending = null;
    this.busy = true;
    this.figure.classList.add('busy');
    try {
      const frame = await this.#request({ type: 'render', scene });
      this.#draw(frame);
      this.onframe(this, frame);
    } catch (error) {
      this.onerror(this, error);
    } finally {
      this.busy = false;
      if (this.pending !== null) this.#next();
      else this.figure.classList.remove('busy');
    }
  }

  #draw(frame) {
    if (this.canvas.width !== frame.width || this.canvas.height !== frame.height) {
      this.canvas.width = frame.width;
      this.canvas.height = frame.height;
    }
    this.context.putImageData(new ImageData(frame.pixels, frame.width, frame.height), 0, 0);
    this.frames += 1;
    this.times.push(frame.ms);
    if (this.times.length > HISTORY) this.times.shift();
    this.lastStats = frame.stats;
    this.timeEl.textContent = t('panel.time', { ms: frame.ms.toFixed(1) });
    const s = frame.stats;
    this.statsEl.textContent = t('panel.stats', {
      evaluations: formatCount(s.lighting_evaluations),
      polygons: formatCount(s.rasterized),
      pixels: formatCount(s.fragments_shaded),
    });
  }
}
