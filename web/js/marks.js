// Marks drawn over a panel, never into its pixels: the inspected pixel, its
// scanline, the polygon the scanline walk went round with the span from P to
// Q (the inspector's diagram letters them), and the profile's row
// or line; and the lights' markers (js/lights.js), which a drag moves. An SVG laid over the canvas, in the image's pixel coordinates
// (pixel (x, y) covers x..x+1, y..y+1), so that a mark sits on the pixel it
// names at any display size; strokes and labels keep their size on the screen.

import { beforeNextPaint } from './dom.js';

const SVG = 'http://www.w3.org/2000/svg';

function node(tag, attrs, text) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

export class Marks {
  /** Lays an SVG over `canvas` (inside its positioned parent). */
  constructor(canvas) {
    this.canvas = canvas;
    this.svg = node('svg', { class: 'marks', 'aria-hidden': 'true', preserveAspectRatio: 'none' });
    canvas.after(this.svg);
    this.pixel = null;
    this.profile = null;
    this.inspection = null;
    this.preview = null;
    this.lights = [];
    this.circle = false;
    /**
     * The canvas's width on the screen, CSS pixels, as the ResizeObserver
     * last saw it: reading `clientWidth` in `draw` would force a layout of
     * the page on every frame.
     */
    this.shown = null;
    new ResizeObserver(() => {
      this.shown = canvas.clientWidth;
      this.draw();
    }).observe(canvas);
  }

  /** Sets what to mark (undefined leaves a mark as it is); draws before the next paint. */
  set({ pixel, profile, inspection, preview, lights, circle } = {}) {
    if (lights !== undefined) this.lights = lights;
    if (circle !== undefined) this.circle = circle;
    if (pixel !== undefined) this.pixel = pixel;
    if (profile !== undefined) this.profile = profile;
    if (inspection !== undefined) this.inspection = inspection;
    if (preview !== undefined) this.preview = preview;
    beforeNextPaint(this.draw);
  }

  draw = () => {
    const { width: w, height: h } = this.canvas;
    const shown = this.shown ?? this.canvas.clientWidth;
    this.svg.replaceChildren();
    if (!shown) return;
    this.svg.setAttribute('viewBox', `0 0 ${w} ${h}`);
    // Image pixels per CSS pixel: sizes on the screen, in image units.
    const u = w / shown;
    const add = (tag, attrs, text) => this.svg.append(node(tag, { 'vector-effect': 'non-scaling-stroke', ...attrs }, text));

    const line = this.preview ?? this.profile?.line;
    if (line) {
      const [x0, y0, x1, y1] = line;
      add('line', { x1: x0, y1: y0, x2: x1, y2: y1, class: 'mark-profile' });
      for (const [x, y] of [[x0, y0], [x1, y1]]) add('circle', { cx: x, cy: y, r: 3 * u, class: 'mark-profile-end' });
    } else if (this.profile) {
      // Two lines just outside the row, so the row's own pixels stay in view.
      const y = this.profile.row;
      add('line', { x1: 0, y1: y, x2: w, y2: y, class: 'mark-profile' });
      add('line', { x1: 0, y1: y + 1, x2: w, y2: y + 1, class: 'mark-profile' });
    }

    const m = this.inspection;
    if (m && m.row !== null && m.row !== undefined) {
      // The scanline through the pixel, faint across the image, bold from P to Q below.
      add('line', { x1: 0, y1: m.row + 0.5, x2: w, y2: m.row + 0.5, class: 'mark-scanline' });
    }
    // The polygon and the span from P to Q, unlabelled: the letters are in the
    // inspector's diagram beside the panels, so that no text covers the picture.
    if (m && m.walked.length >= 3) {
      add('polygon', { points: m.walked.map(([x, y]) => `${x},${y}`).join(' '), class: 'mark-polygon' });
    }
    if (m && m.p && m.q) {
      add('line', { x1: m.p[0], y1: m.p[1], x2: m.q[0], y2: m.q[1], class: 'mark-span' });
      for (const [x, y] of [m.p, m.q]) add('circle', { cx: x, cy: y, r: 3 * u, class: 'mark-point' });
    }

    // The lights: a numbered disc in the light's colour each, hollow when the
    // light is behind the model; while one is dragged, the circle of directions.
    if (this.circle && this.lights.length) {
      const r = this.circle * Math.min(w, h);
      add('circle', { cx: w / 2, cy: h / 2, r, class: 'mark-light-circle' });
    }
    for (const m of this.lights) {
      const g = node('g', { class: `mark-light${m.behind ? ' behind' : ''}${m.active ? ' active' : ''}`, 'data-light': m.k });
      g.append(node('circle', { cx: m.x, cy: m.y, r: 8 * u, 'vector-effect': 'non-scaling-stroke', fill: m.behind ? 'none' : m.color, stroke: m.behind ? m.color : '#000' }));
      g.append(node('text', { x: m.x, y: m.y + 4 * u, 'text-anchor': 'middle', 'font-size': 11 * u, class: 'mark-label' }, String(m.k + 1)));
      this.svg.append(g);
    }

    if (this.pixel) {
      const [x, y] = this.pixel;
      // The pixel's square, and ticks pointing at it from four sides.
      const gap = Math.max(1.5, 3 * u);
      const tick = 12 * u;
      const ticks = [
        [x + 0.5, y - gap - tick, x + 0.5, y - gap],
        [x + 0.5, y + 1 + gap, x + 0.5, y + 1 + gap + tick],
        [x - gap - tick, y + 0.5, x - gap, y + 0.5],
        [x + 1 + gap, y + 0.5, x + 1 + gap + tick, y + 0.5],
      ];
      // A dark edge under each stroke keeps the mark visible on any colour.
      for (const cls of ['mark-pixel-under', 'mark-pixel']) {
        add('rect', { x, y, width: 1, height: 1, class: cls });
        for (const [ax, ay, bx, by] of ticks) add('line', { x1: ax, y1: ay, x2: bx, y2: by, class: cls });
      }
    }
  };
}
