// The three panels: each a canvas drawn by its own worker. A panel renders
// the newest frame it was asked for: while a frame is being drawn, later
// requests replace each other and only the last is drawn next, so dragging
// never queues up stale frames. Instruments ask the same worker with `ask`,
// between frames.
//
// When the three panels draw the same scene with their three methods and
// nothing else (no overlays, no error map), a `PanelGroup` asks for the three
// frames at once: the geometry is transformed, set up, binned and walked once
// instead of three times. With two cores, the first two panels' workers each
// draw half of the three frames' rows (`part`), at the same time, and the
// halves are joined here; with one, the first panel's worker draws them
// whole. Its frames reach each panel as its own would.
import { t, plural, formatCount, formatNumber } from './i18n.js';
import { el, put, beforeNextPaint, paintPending } from './dom.js';
import { Marks } from './marks.js';
import { joinParts } from './shadelab.js';

/** How many recent frame times each panel keeps (for the page and its tests). */
const HISTORY = 240;
/** The caption's time is the median of this many recent frames. */
export const CAPTION_FRAMES = 9;
/**
 * A frame still being drawn after this long dims its panel's caption
 * (`busy`). Not at once: the class change makes the page restyle and
 * repaint while the workers draw, which on a two-core machine takes their
 * cores (an orbit step took 1.5–3.7 ms longer: BENCHMARKS.md, "The page's
 * own work during a frame").
 */
const BUSY_AFTER_MS = 150;

/** The median of `xs`. */
export function median(xs) {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
}

/** Draws RGBA `pixels` of `width` × `height` into `canvas`. */
export function paint(canvas, context, { width, height, pixels }) {
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  context.putImageData(new ImageData(pixels, width, height), 0, 0);
}

/** A figure with a canvas that is painted from images (the exact surface's panel). */
export class ImagePanel {
  constructor(method, figure) {
    this.method = method;
    this.figure = figure;
    this.canvas = figure.querySelector('canvas');
    this.context = this.canvas.getContext('2d', { willReadFrequently: true });
    this.statsEl = figure.querySelector('.stats');
    this.marks = new Marks(this.canvas);
  }

  show(image) {
    paint(this.canvas, this.context, image);
    this.marks.draw();
  }
}

export class Panel {
  constructor(method, figure, module) {
    this.method = method;
    this.figure = figure;
    this.canvas = figure.querySelector('canvas');
    // Frames arrive as pixels, and instruments read pixels back: keep the canvas in memory.
    this.context = this.canvas.getContext('2d', { willReadFrequently: true });
    this.timeEl = figure.querySelector('.time');
    // The caption's time, kept: `relabel` writes into these spans.
    this.timeLabelEl = el('span', { class: 'time-label' });
    this.timeValueEl = el('span', { class: 'time-value' });
    this.timeEl.replaceChildren(this.timeLabelEl, this.timeValueEl);
    this.variantEl = figure.querySelector('.variant');
    this.rasterEl = figure.querySelector('.raster');
    this.statsEl = figure.querySelector('.stats');
    this.marks = new Marks(this.canvas);
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    this.nextId = 1;
    this.waiting = new Map();
    /** Whether this panel's worker is drawing a frame for it. */
    this.drawing = false;
    /** Whether a `PanelGroup` frame for this panel is being drawn. */
    this.groupBusy = false;
    this.pending = null;
    /** The pixels' buffer of the last frame painted, given back to the worker for the next. */
    this.spare = null;
    /** The timer that dims the caption of a slow frame (`showBusySoon`). */
    this.busyTimer = 0;
    this.times = [];
    /** Each recent frame's `at` (see #draw), as `times`. */
    this.timings = [];
    this.frames = 0;
    /** The last frame drawn: its request's generation, size, counts, error map. */
    this.last = null;
    this.onframe = () => {};
    this.onerror = () => {};
    this.worker.onmessage = (event) => this.#receive(event.data);
    this.ready = this.ask({ type: 'init', module });
  }

  /** Whether a frame for this panel is being drawn (by its worker or a group). */
  get busy() {
    return this.drawing || this.groupBusy;
  }

  /** Sends one request to this panel's worker; resolves to its answer. */
  ask(msg, transfer = []) {
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

  /**
   * Parses the user's file in this panel's engine; resolves to {summary,
   * mesh}: the mesh as bytes for the other panels' `adoptFile`.
   */
  async loadFile(name, bytes) {
    const answer = await this.ask({ type: 'load-file', name, bytes, share: true });
    return { summary: answer.summary, mesh: answer.mesh };
  }

  /** Gives this panel's engine the mesh another panel parsed; resolves to its summary. */
  async adoptFile(name, mesh) {
    const answer = await this.ask({ type: 'adopt-file', name, mesh });
    return answer.summary;
  }

  /**
   * Asks for a frame: `{scene, overlays, errors, generation}` (see worker.js);
   * the newest request wins.
   */
  render(request) {
    this.pending = request;
    if (!this.busy) this.#next();
  }

  /** After a group's frame: draws what was asked for meanwhile. */
  resume() {
    if (this.drawing) return;
    if (this.pending !== null) {
      this.#next();
      return;
    }
    clearTimeout(this.busyTimer);
    if (this.figure.classList.contains('busy')) this.figure.classList.remove('busy');
  }

  /** Dims the caption (`busy`) if a frame is still being drawn after BUSY_AFTER_MS. */
  showBusySoon() {
    clearTimeout(this.busyTimer);
    this.busyTimer = setTimeout(() => {
      if (this.busy) this.figure.classList.add('busy');
    }, BUSY_AFTER_MS);
  }

  /** The buffer of the last frame painted, for the next frame's pixels (once). */
  takeSpare() {
    const spare = this.spare;
    this.spare = null;
    return spare;
  }

  /** Resolves once no frame is being drawn or waiting. */
  idle() {
    const still = () => !this.busy && this.pending === null && !paintPending();
    if (still()) return Promise.resolve();
    return new Promise((resolve) => {
      const check = () => (still() ? resolve() : setTimeout(check, 5));
      check();
    });
  }

  async #next() {
    const request = this.pending;
    this.pending = null;
    this.drawing = true;
    this.showBusySoon();
    try {
      const { generation, gouraudSpecular, settling, ...msg } = request;
      const spare = this.takeSpare();
      const sent = performance.timeOrigin + performance.now();
      const frame = await this.ask({ type: 'render', ...msg, spare }, spare ? [spare] : []);
      frame.at.sent = sent;
      frame.at.arrived = performance.timeOrigin + performance.now();
      frame.generation = generation;
      frame.gouraudSpecular = gouraudSpecular;
      frame.overlays = msg.overlays;
      frame.settling = !!settling;
      this.show(frame);
    } catch (error) {
      this.onerror(this, error);
    } finally {
      this.drawing = false;
      // While a group draws, what was asked for meanwhile waits for it (`resume`).
      if (!this.groupBusy) this.resume();
    }
  }

  /**
   * Paints a frame this panel's worker or a group drew and reports it; a
   * frame of an older request than the one shown (one that was on its way
   * while a group drew a newer one) is dropped.
   */
  show(frame) {
    if (this.last && frame.generation < this.last.generation) return;
    this.#draw(frame);
    this.onframe(this, frame);
  }

  /** Colours the last error map on `scale` (the three panels share one scale). */
  async recolour(scale) {
    if (!this.last?.errors || this.last.errors.scale === scale) return;
    const answer = await this.ask({ type: 'heat', scale, overlays: this.last.overlays ?? '' });
    paint(this.canvas, this.context, { width: this.last.width, height: this.last.height, pixels: answer.pixels });
    this.last.errors.scale = answer.scale;
    this.marks.draw();
  }

  #draw(frame) {
    // Times of frames drawn together and apart are not comparable: each
    // history holds one kind. A frame of the first view drawn again
    // (`settling`, main.js) replaces the history: the frames before it ran
    // while the browser was still compiling the engine.
    if (frame.settling || (this.last && !!this.last.together !== !!frame.together)) {
      this.times.length = 0;
      this.timings.length = 0;
    }
    paint(this.canvas, this.context, frame);
    // When the request left, reached the worker, came back and was painted
    // (ms since the epoch): where a frame's latency goes (bench/viewer).
    frame.at.painted = performance.timeOrigin + performance.now();
    // The canvas holds its own copy now: the buffer can carry the next frame.
    this.spare = frame.pixels.buffer;
    beforeNextPaint(this.decorate);
    this.frames += 1;
    this.times.push(frame.ms);
    this.timings.push(frame.at);
    if (this.times.length > HISTORY) this.times.shift();
    if (this.timings.length > HISTORY) this.timings.shift();
    const { pixels, exact, bar, ...kept } = frame;
    this.last = kept;
  }

  /** The marks and the caption of the last frame, drawn before the paint that shows it. */
  decorate = () => {
    this.marks.draw();
    this.relabel();
  };

  /** The caption's time: the median render time of the last frames, and how many. */
  captionTime() {
    const recent = this.times.slice(-CAPTION_FRAMES);
    return { ms: recent.length ? median(recent) : 0, frames: recent.length };
  }

  /**
   * Writes the caption and the counts under the panel in the current
   * language; the Gouraud panel's says whether its vertex lighting had the
   * specular term.
   */
  relabel() {
    const f = this.last;
    if (!f) return;
    // Only what changed is written (`put`): the caption is rewritten for
    // every frame, and a text set again, even unchanged, is laid out again.
    if (this.variantEl) {
      const key = f.gouraudSpecular ? 'panel.gouraud.specular' : 'panel.gouraud.noSpecular';
      put(this.variantEl, 'textContent', t(key));
      put(this.variantEl, 'title', t(`${key}.title`));
      put(this.variantEl.dataset, 'specular', String(!!f.gouraudSpecular));
    }
    const { ms, frames } = this.captionTime();
    // A group's frame took the time of the three panels together.
    const label = f.together ? 'panel.time.together' : 'panel.time';
    put(this.timeLabelEl, 'textContent', plural(`${label}.label`, frames));
    put(this.timeValueEl, 'textContent', t('panel.time', { ms: formatNumber(ms, 1) }));
    put(this.timeEl, 'title', plural(`${label}.title`, frames));
    put(this.timeEl.dataset, 'together', String(!!f.together));
    put(this.rasterEl, 'textContent', t(`panel.raster.${f.rasterizer}`));
    put(this.rasterEl.dataset, 'rasterizer', f.rasterizer);
    put(this.rasterEl, 'title', t(`panel.raster.${f.rasterizer}.title`));
    if (f.errors) {
      const e = f.errors;
      put(this.statsEl, 'textContent', t('panel.errors', {
        mean: formatNumber(e.mean, 2),
        max: formatNumber(e.max, 1),
        compared: formatCount(e.compared),
      }));
      return;
    }
    const s = f.stats;
    put(this.statsEl, 'textContent', t(`panel.stats.${this.method}`, {
      evaluations: plural('count.evaluations', s.lighting_evaluations),
      polygons: plural('count.polygonsDrawn', s.rasterized),
      pixels: plural('count.pixelsShaded', s.fragments_shaded),
    }));
  }
}

/**
 * The three panels drawn in one request (see the top of this file): to the
 * first panel's worker, or in `parts` parts of their rows to as many panels'
 * workers at once. Like a panel, it draws the newest request and drops the
 * ones replaced while a frame was being drawn; while its frame is drawn, the
 * panels' own requests wait, and a panel's own frame that was on its way is
 * dropped if the group's is newer.
 */
export class PanelGroup {
  constructor(panels, parts = 1) {
    this.panels = panels;
    /** How many workers draw a frame's rows, 1 to the number of panels. */
    this.parts = parts;
    this.pending = null;
    this.busy = false;
    /** Each part's pixel buffers of the last frame, given back to its worker for the next. */
    this.partSpares = [];
    this.onerror = () => {};
  }

  /** Asks for the three frames of `{scene, generation, gouraudSpecular}`; the newest request wins. */
  render(request) {
    this.pending = request;
    if (!this.busy) this.#next();
  }

  /**
   * The three frames of `scene`, {frames, ms, at}: from the first panel's
   * worker, or in parts (`ms` then the slowest part's, as they are drawn at
   * the same time).
   */
  async #draw(scene, spares) {
    const parts = Math.max(1, Math.min(this.parts, this.panels.length));
    if (parts === 1) {
      const answer = await this.panels[0].ask(
        { type: 'render-methods', scene, spares },
        spares.filter((s) => s),
      );
      return answer;
    }
    const given = this.partSpares;
    this.partSpares = [];
    const answers = await Promise.all(
      Array.from({ length: parts }, (_, k) => {
        const back = given[k] ?? [];
        return this.panels[k].ask({ type: 'render-methods', scene, part: [k, parts], spares: back }, back.filter((s) => s));
      }),
    );
    const frames = [0, 1, 2].map((m) =>
      joinParts(answers.map((a) => ({ frame: a.frames[m], rows: a.rows })), spares[m]),
    );
    const shown = new Set(frames.map((f) => f.pixels.buffer));
    this.partSpares = answers.map((a) => a.frames.map((f) => (shown.has(f.pixels.buffer) ? null : f.pixels.buffer)));
    return {
      frames,
      ms: Math.max(...answers.map((a) => a.ms)),
      at: {
        received: Math.min(...answers.map((a) => a.at.received)),
        posted: Math.max(...answers.map((a) => a.at.posted)),
      },
    };
  }

  async #next() {
    const request = this.pending;
    this.pending = null;
    this.busy = true;
    for (const p of this.panels) {
      p.groupBusy = true;
      p.showBusySoon();
    }
    try {
      const { generation, gouraudSpecular, scene, settling } = request;
      const spares = this.panels.map((p) => p.takeSpare());
      const sent = performance.timeOrigin + performance.now();
      const answer = await this.#draw(scene, spares);
      const arrived = performance.timeOrigin + performance.now();
      answer.frames.forEach((frame, k) => {
        frame.ms = answer.ms;
        frame.at = { ...answer.at, sent, arrived };
        frame.generation = generation;
        frame.gouraudSpecular = gouraudSpecular;
        frame.overlays = '';
        frame.together = true;
        frame.settling = !!settling;
        this.panels[k].show(frame);
      });
    } catch (error) {
      this.onerror(this.panels[0], error);
    } finally {
      this.busy = false;
      for (const p of this.panels) p.groupBusy = false;
      if (this.pending !== null) this.#next();
      else for (const p of this.panels) p.resume();
    }
  }
}
