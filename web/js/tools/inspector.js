// The pixel inspector: for the chosen pixel, what each panel's method did
// there, with the textbook's formulas filled in. Each panel's worker
// inspects its own method (shadelab-lab's `inspect`, the same text as
// `shadelab explain`); the page lays the lines out and marks the polygon,
// the scanline and P and Q on the panels. Beside each method's account, a
// magnifier shows the MAG_SPAN × MAG_SPAN pixels around the inspected pixel
// (or, while the pointer is over a panel, around the pointer) MAG_ZOOM
// times enlarged with the pixel grid: the picture itself stays uncovered.
import { t, lab, language } from '../i18n.js';
import { el } from '../dom.js';
import { Controls } from '../controls.js';

/** The magnifier: this many pixels a side (odd: the pixel sits in the middle), each drawn this many times as large. */
export const MAG_SPAN = 15;
export const MAG_ZOOM = 8;

/**
 * Draws the MAG_SPAN² pixels of `source` (a canvas) around (x, y) into
 * `canvas`, MAG_ZOOM× with the pixel grid, the middle pixel outlined; pixels
 * outside the picture are left dark grey.
 */
export function drawMagnifier(canvas, source, x, y) {
  const dpr = window.devicePixelRatio || 1;
  const side = MAG_SPAN * MAG_ZOOM;
  canvas.width = Math.round(side * dpr);
  canvas.height = Math.round(side * dpr);
  const g = canvas.getContext('2d');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.fillStyle = '#2a2a33';
  g.fillRect(0, 0, side, side);
  const half = (MAG_SPAN - 1) / 2;
  const x0 = x - half;
  const y0 = y - half;
  // The pixels that exist, enlarged without smoothing.
  const sx = Math.max(0, x0);
  const sy = Math.max(0, y0);
  const sw = Math.min(source.width, x0 + MAG_SPAN) - sx;
  const sh = Math.min(source.height, y0 + MAG_SPAN) - sy;
  g.imageSmoothingEnabled = false;
  if (sw > 0 && sh > 0) g.drawImage(source, sx, sy, sw, sh, (sx - x0) * MAG_ZOOM, (sy - y0) * MAG_ZOOM, sw * MAG_ZOOM, sh * MAG_ZOOM);
  g.strokeStyle = 'rgba(128, 128, 140, 0.55)';
  g.lineWidth = 1 / dpr;
  g.beginPath();
  for (let k = 0; k <= MAG_SPAN; k++) {
    const at = k * MAG_ZOOM + 0.5 / dpr;
    g.moveTo(at, 0);
    g.lineTo(at, side);
    g.moveTo(0, at);
    g.lineTo(side, at);
  }
  g.stroke();
  g.lineWidth = 2;
  g.strokeStyle = '#000';
  g.strokeRect(half * MAG_ZOOM - 1, half * MAG_ZOOM - 1, MAG_ZOOM + 2, MAG_ZOOM + 2);
  g.strokeStyle = '#ffd166';
  g.strokeRect(half * MAG_ZOOM, half * MAG_ZOOM, MAG_ZOOM, MAG_ZOOM);
}

const SVG = 'http://www.w3.org/2000/svg';
const svg = (tag, attrs, text) => {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
};

/**
 * The polygon the scanline walk went round, drawn apart from the picture:
 * its vertices lettered as the account names them, the scanline, P, Q and
 * the pixel centre O. `m` is a method's inspection; `size` the diagram's side.
 */
export function polygonDiagram(m, pixel, size = 150) {
  const out = svg('svg', { class: 'diagram', viewBox: `0 0 ${size} ${size}`, role: 'img', 'aria-label': t('inspector.diagram') });
  const pts = [...m.walked];
  const o = [pixel[0] + 0.5, pixel[1] + 0.5];
  const all = [...pts, o, ...(m.p ? [m.p, m.q] : [])];
  const xs = all.map((v) => v[0]);
  const ys = all.map((v) => v[1]);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const margin = 18;
  const k = (size - 2 * margin) / Math.max(x1 - x0, y1 - y0, 1e-6);
  const at = ([x, y]) => [margin + (x - x0) * k + ((size - 2 * margin) - (x1 - x0) * k) / 2, margin + (y - y0) * k + ((size - 2 * margin) - (y1 - y0) * k) / 2];
  out.append(svg('polygon', { points: pts.map((v) => at(v).join(',')).join(' '), class: 'mark-polygon' }));
  const [cx, cy] = at([pts.reduce((a, v) => a + v[0], 0) / pts.length, pts.reduce((a, v) => a + v[1], 0) / pts.length]);
  pts.forEach((v, i) => {
    const [x, y] = at(v);
    const d = Math.hypot(x - cx, y - cy) || 1;
    out.append(svg('text', { x: x + ((x - cx) / d) * 10, y: y + ((y - cy) / d) * 10 + 4, 'text-anchor': 'middle', class: 'mark-label mark-vertex' }, String.fromCharCode(65 + (i % 26))));
  });
  const [, oy] = at(o);
  out.append(svg('line', { x1: 0, y1: oy, x2: size, y2: oy, class: 'mark-scanline' }));
  if (m.p && m.q) {
    const [px, py] = at(m.p);
    const [qx, qy] = at(m.q);
    out.append(svg('line', { x1: px, y1: py, x2: qx, y2: qy, class: 'mark-span' }));
    for (const [name, x, y, anchor] of [['P', px, py, 'end'], ['Q', qx, qy, 'start']]) {
      out.append(svg('circle', { cx: x, cy: y, r: 3, class: 'mark-point' }));
      out.append(svg('text', { x: x + (anchor === 'end' ? -5 : 5), y: y + 14, 'text-anchor': anchor, class: 'mark-label' }, name));
    }
  }
  const [ox] = at(o);
  out.append(svg('circle', { cx: ox, cy: oy, r: 3.5, class: 'mark-pixel' }));
  out.append(svg('text', { x: ox, y: oy - 7, 'text-anchor': 'middle', class: 'mark-label' }, 'O'));
  return out;
}

/** A line that is a formula or a vector, not a sentence: set it in monospace. */
const FORMULA = /^(?:[A-Za-z]{1,2}(?:_[A-Za-z]+)?|r|h|l|n) = /;

export class Inspector {
  constructor(page) {
    this.page = page;
    this.key = '';
    this.answer = null;
    /** The pixel under the pointer on a panel, or null: the magnifiers show it. */
    this.hovered = null;
    this.magnifiers = [];
  }

  /** The pointer is over pixel (x, y) of a panel (null: it left). */
  hover(at) {
    this.hovered = at;
    this.drawMagnifiers();
  }

  /** Draws each method's magnifier around the pixel under the pointer, else the inspected one. */
  drawMagnifiers() {
    const at = this.hovered ?? this.page.state().pixel;
    for (const { method, canvas, caption } of this.magnifiers) {
      const panel = this.page.panels.find((p) => p.method === method);
      if (!at || !panel || !canvas.isConnected) continue;
      drawMagnifier(canvas, panel.canvas, at[0], at[1]);
      caption.textContent = t('inspector.magnifier', { zoom: MAG_ZOOM, span: MAG_SPAN, x: at[0], y: at[1] });
    }
  }

  build(section) {
    const page = this.page;
    const s = page.state;
    section.append(el('h2', { text: t('tab.inspector') }));
    section.append(el('details', { class: 'explain' }, [el('summary', { text: t('explain.what') }), el('p', { text: lab('about.inspector') })]));
    const controls = el('div', { class: 'tool-controls' });
    section.append(controls);
    this.controls = new Controls(controls, () => page.changed());
    this.controls.vec3(controls, {
      name: 'pixel', label: t('inspector.pixel'), labels: ['x', 'y'], step: 1,
      get: () => s().pixel ?? [null, null],
      set: (v) => {
        const size = s().size;
        const [x, y] = v.map((c) => (c === null || Number.isNaN(c) ? 0 : Math.min(size - 1, Math.max(0, Math.round(c)))));
        s().pixel = [x, y];
      },
    });
    this.controls.button(controls, { label: t('inspector.clear'), onclick: () => { s().pixel = null; page.changed(); } });
    this.output = el('div', { class: 'inspection', 'aria-live': 'polite' });
    section.append(this.output);
    this.key = '';
    this.#render();
  }

  refresh() {
    this.controls?.refresh();
  }

  /** Inspects the pixel in each panel's worker, when the scene, pixel or language changed. */
  async update() {
    const page = this.page;
    const st = page.state();
    if (!st.pixel) {
      this.answer = null;
      this.key = '';
      this.#render();
      return;
    }
    const lang = language();
    const scenes = page.panels.map((p) => page.sceneFor(p.method));
    const key = JSON.stringify([scenes, st.pixel, lang]);
    if (key === this.key) return;
    this.key = key;
    const generation = page.generation;
    const [x, y] = st.pixel;
    try {
      const replies = await Promise.all(page.panels.map((p, k) => p.ask({ type: 'inspect', scene: scenes[k], x, y, lang })));
      if (generation !== page.generation || key !== this.key) return;
      const inspections = replies.map((r) => r.inspection);
      this.answer = {
        x,
        y,
        header: inspections[0].header,
        methods: inspections.map((i) => i.methods[0]),
        // What `shadelab explain` prints for the same scene and pixel.
        text: [inspections[0].header, ...inspections.map((i) => i.methods[0].text)].join('\n'),
      };
      this.error = null;
    } catch (error) {
      if (key !== this.key) return;
      this.answer = null;
      this.error = t('error.instrument', { message: error.message });
    }
    this.#render();
  }

  /** Whether the inspection shown is that of the current scene and pixel. */
  current() {
    return this.answer !== null;
  }

  /** Forgets the inspection (the scene changed); the marks go with it. */
  invalidate() {
    for (const p of this.page.panels) p.marks.set({ inspection: null });
  }

  #render() {
    const out = this.output;
    if (!out) return;
    out.replaceChildren();
    const st = this.page.state();
    if (this.error) {
      out.append(el('p', { class: 'tool-error', text: this.error }));
      return;
    }
    if (!st.pixel || !this.answer) {
      out.append(el('p', { class: 'hint', text: t('inspector.pick') }));
      for (const p of this.page.panels) p.marks.set({ inspection: null });
      return;
    }
    const a = this.answer;
    const header = el('div', { class: 'inspect-header' });
    a.header.trimEnd().split('\n').forEach((line, k) => header.append(el(k === 0 ? 'h3' : 'p', { text: line })));
    out.append(header);
    const columns = el('div', { class: 'inspect-methods' });
    out.append(columns);
    this.magnifiers = [];
    for (const m of a.methods) {
      const lines = m.text.trimEnd().split('\n');
      const title = lines.shift().replace(/^== /, '');
      const [r, g, b] = m.color;
      const canvas = el('canvas', { class: 'magnifier', role: 'img', 'aria-label': t('inspector.magnifier.label', { method: title }) });
      const caption = el('figcaption', { class: 'hint' });
      this.magnifiers.push({ method: m.method, canvas, caption });
      const article = el('article', { class: 'inspect-method', 'data-method': m.method }, [
        el('h3', {}, [
          el('span', { class: 'swatch', style: { background: `rgb(${r}, ${g}, ${b})` }, 'aria-hidden': 'true' }),
          el('span', { text: title }),
        ]),
        el('figure', { class: 'magnify' }, [canvas, m.covered && m.walked.length >= 3 ? polygonDiagram(m, [a.x, a.y]) : null, caption]),
      ]);
      for (const line of lines) {
        const indent = line.length - line.trimStart().length;
        const text = line.trim();
        const level = Math.max(0, Math.round((indent - 3) / 2));
        const row = el('div', { class: `line level-${Math.min(level, 3)}${FORMULA.test(text) ? ' formula' : ''}` });
        // The walk's own value beside the textbook formula's: "[stepped: (…)]".
        const stepped = text.match(/^(.*?)(\s+\[[^\]]+\])$/);
        if (stepped) row.append(`${stepped[1]} `, el('span', { class: 'stepped', text: stepped[2].trim() }));
        else row.textContent = text;
        article.append(row);
      }
      columns.append(article);
    }
    this.drawMagnifiers();
    for (const p of this.page.panels) {
      const m = a.methods.find((q) => q.method === p.method);
      p.marks.set({ inspection: m && m.covered ? m : null });
    }
  }
}
