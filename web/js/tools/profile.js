// The scanline profile: intensity along a row (or a line) for flat, Gouraud
// and Phong shading and the exact surface, with its change from pixel to
// pixel below, polygon edges marked. The numbers are shadelab-lab's
// `profile` (as `shadelab profile` plots them), computed by one panel's
// worker; the plot is drawn here on a canvas.
import { t, lab, formatNumber } from '../i18n.js';
import { el } from '../dom.js';
import { Controls } from '../controls.js';
import { drawPlot } from '../plot.js';

/** Curve colours, the same as the legend's. */
export const CURVE_COLORS = { flat: '#f5a623', gouraud: '#4fb3ff', phong: '#7ee07a', exact: '#ffffff' };
const EDGE = 'rgba(255, 120, 200, 0.55)';
const FAN_EDGE = 'rgba(255, 120, 200, 0.35)';

export class ProfileTool {
  constructor(page) {
    this.page = page;
    this.key = '';
    this.data = null;
    this.hidden = new Set();
    this.cursor = null;
  }

  build(section) {
    const page = this.page;
    const s = page.state;
    section.append(el('h2', { text: t('tab.profile') }));
    section.append(el('details', { class: 'explain' }, [
      el('summary', { text: t('explain.what') }),
      el('p', { text: lab('about.profile') }),
      el('p', { text: lab('about.mach_bands') }),
    ]));
    const box = el('div', { class: 'tool-controls' });
    section.append(box);
    const c = new Controls(box, () => page.changed());
    this.controls = c;
    c.select(box, {
      name: 'profile-along', label: t('profile.along'),
      options: () => [['none', t('profile.along.none')], ['row', t('profile.along.row')], ['line', t('profile.along.line')]],
      get: () => (s().profile ? (s().profile.line ? 'line' : 'row') : 'none'),
      set: (v) => {
        const n = s().size;
        const mid = Math.floor(n / 2);
        if (v === 'none') s().profile = null;
        else if (v === 'row') s().profile = { row: s().pixel?.[1] ?? mid };
        else s().profile = { line: [n * 0.1, n * 0.9, n * 0.9, n * 0.1].map((x) => Number(x.toFixed(1))) };
      },
    });
    c.range(box, {
      name: 'profile-row', label: t('profile.row'), min: 0, max: () => s().size - 1, step: 1,
      get: () => s().profile?.row ?? 0,
      set: (v) => (s().profile = { row: Math.round(v) }),
      visible: () => s().profile?.row !== undefined,
    });
    for (const [k, label] of [[0, 'profile.from'], [2, 'profile.to']]) {
      c.vec3(box, {
        name: `profile-${k ? 'to' : 'from'}`, label: t(label), labels: ['x', 'y'], step: 0.5,
        get: () => (s().profile?.line ?? [0, 0, 0, 0]).slice(k, k + 2),
        set: (v) => {
          const line = [...(s().profile?.line ?? [0, 0, 0, 0])];
          line[k] = v[0];
          line[k + 1] = v[1];
          s().profile = { line };
        },
      });
    }
    this.lineRows = [...box.querySelectorAll('.vec')].map((v) => v.closest('.row'));
    box.append(el('p', { class: 'hint', text: t('profile.pick') }));

    this.legend = el('div', { class: 'legend' });
    this.title = el('h3', { class: 'plot-title' });
    this.intensity = el('canvas', { class: 'plot plot-intensity', role: 'img', 'aria-label': lab('about.profile') });
    this.derivativeTitle = el('h3', { class: 'plot-title', text: lab('plot.derivative_title') });
    this.derivative = el('canvas', { class: 'plot plot-derivative', role: 'img', 'aria-label': lab('plot.derivative_title') });
    this.readout = el('p', { class: 'readout', 'aria-live': 'polite' });
    this.message = el('p', { class: 'hint' });
    this.figure = el('div', { class: 'profile-plots' }, [this.title, this.legend, this.intensity, this.derivativeTitle, this.derivative, this.readout]);
    section.append(this.message, this.figure);
    for (const canvas of [this.intensity, this.derivative]) {
      canvas.addEventListener('pointermove', (e) => this.#hover(canvas, e));
      canvas.addEventListener('pointerleave', () => { this.cursor = null; this.#draw(); });
      canvas.addEventListener('click', (e) => this.#inspectAt(canvas, e));
    }
    new ResizeObserver(() => this.#draw()).observe(this.intensity);
    this.key = '';
    this.refresh();
    this.#draw();
  }

  refresh() {
    if (!this.controls) return;
    this.controls.refresh();
    const line = !!this.page.state().profile?.line;
    for (const row of this.lineRows) row.hidden = !line;
  }

  async update() {
    const page = this.page;
    const st = page.state();
    if (!st.profile) {
      this.data = null;
      this.key = '';
      this.#draw();
      return;
    }
    // Any panel's scene will do: the profile draws all three methods. The flat
    // panel's worker is the least busy.
    const scene = page.sceneFor('flat');
    const key = JSON.stringify([scene, st.profile]);
    if (key === this.key) return;
    this.key = key;
    const generation = page.generation;
    try {
      const reply = await page.panels[0].ask({ type: 'profile', scene, ...st.profile });
      if (generation !== page.generation || key !== this.key) return;
      this.data = { ...reply.profile, along: st.profile };
      this.error = null;
    } catch (error) {
      if (key !== this.key) return;
      this.data = null;
      this.error = t('error.instrument', { message: error.message });
    }
    this.#draw();
  }

  /** The sample under the pointer. */
  #sampleAt(canvas, e) {
    if (!this.data || !this.map) return null;
    const r = canvas.getBoundingClientRect();
    const map = canvas === this.intensity ? this.map.intensity : this.map.derivative;
    const k = Math.round(map.toX(e.clientX - r.left) - this.x0);
    return k >= 0 && k < this.data.pixels.length ? k : null;
  }

  #hover(canvas, e) {
    const k = this.#sampleAt(canvas, e);
    if (k === this.cursor) return;
    this.cursor = k;
    this.#draw();
  }

  #inspectAt(canvas, e) {
    const k = this.#sampleAt(canvas, e);
    if (k === null) return;
    this.page.inspectPixel(...this.data.pixels[k]);
  }

  #draw() {
    if (!this.figure) return;
    const d = this.data;
    this.message.textContent = this.error ?? (d ? '' : t('profile.empty'));
    this.message.hidden = !!d && !this.error;
    this.figure.hidden = !d;
    if (!d) return;
    const row = d.along.row !== undefined;
    this.title.textContent = row ? lab('plot.profile_title', { row: d.along.row }) : t('profile.lineTitle', { from: `(${d.along.line[0]}, ${d.along.line[1]})`, to: `(${d.along.line[2]}, ${d.along.line[3]})` });
    // Along a row the axis is x; along a line, the sample's number.
    this.x0 = row && d.pixels.length ? d.pixels[0][0] : 0;
    const xOf = (k) => this.x0 + k;
    const n = d.pixels.length;
    const range = [xOf(-0.5), xOf(n - 0.5)];
    const shown = d.curves.filter((c) => !this.hidden.has(c.kind));
    const style = (kind) => ({ color: CURVE_COLORS[kind], width: kind === 'exact' ? 1.25 : 1.75, dash: kind === 'exact' ? [5, 4] : [] });

    // The legend: a button per curve, pressed while it is shown.
    this.legend.replaceChildren(...d.curves.map((c) => {
      const b = el('button', { type: 'button', class: 'legend-item', 'aria-pressed': String(!this.hidden.has(c.kind)), 'data-kind': c.kind }, [
        el('span', { class: `key key-${c.kind}`, style: { '--key': CURVE_COLORS[c.kind] }, 'aria-hidden': 'true' }),
        el('span', { text: c.kind === 'exact' ? lab('method.exact') : t(`panel.${c.kind}`) }),
      ]);
      b.addEventListener('click', () => {
        if (this.hidden.has(c.kind)) this.hidden.delete(c.kind);
        else this.hidden.add(c.kind);
        this.#draw();
      });
      return b;
    }));
    const edgeCurve = d.curves.find((c) => c.kind === 'gouraud');
    const polygonEdges = new Set(edgeCurve.polygon_edges);
    const vlines = [
      ...edgeCurve.polygon_edges.map((k) => ({ x: xOf(k + 0.5), color: EDGE })),
      ...edgeCurve.edges.filter((k) => !polygonEdges.has(k)).map((k) => ({ x: xOf(k + 0.5), color: FAN_EDGE, dash: [2, 3] })),
    ];
    if (this.cursor !== null) vlines.push({ x: xOf(this.cursor), color: 'rgba(255, 255, 255, 0.8)' });
    this.map = {};
    this.map.intensity = drawPlot(this.intensity, {
      x: range, y: [0, 255],
      series: shown.map((c) => ({ ...style(c.kind), points: c.values.map((v, k) => [xOf(k), v]) })),
      vlines,
      xLabel: row ? lab('plot.position') : t('profile.sample'),
      yLabel: lab('plot.intensity'),
    });
    // Flat shading's jumps would flatten every other curve: the scale follows
    // the smooth curves, and the jumps run off it.
    // The steep fall at a silhouette would do the same: the scale covers most
    // of the slopes (the 95th percentile), and the rest run off it.
    const smooth = shown.filter((c) => c.kind !== 'flat');
    const slopes = (smooth.length ? smooth : shown).flatMap((c) => c.derivative.filter((v) => v !== null).map(Math.abs)).sort((a, b) => a - b);
    const typical = slopes.length ? slopes[Math.floor(0.95 * (slopes.length - 1))] : 0;
    const extent = Math.min(255, Math.max(0.5, typical * 1.6));
    this.map.derivative = drawPlot(this.derivative, {
      x: range, y: [-extent, extent], zeroLine: true,
      series: shown.map((c) => ({ ...style(c.kind), points: c.derivative.map((v, k) => [xOf(k + 0.5), v]) })),
      vlines,
      xLabel: row ? lab('plot.position') : t('profile.sample'),
      yLabel: t('plot.derivativeAxis'),
    });
    this.intensity.setAttribute('aria-label', this.title.textContent);
    this.derivative.setAttribute('aria-label', lab('plot.derivative_title'));
    if (this.cursor === null) {
      this.readout.textContent = t('profile.hover', { edges: edgeCurve.polygon_edges.length });
    } else {
      const [x, y] = d.pixels[this.cursor];
      const values = d.curves.map((c) => {
        const v = c.values[this.cursor];
        const name = c.kind === 'exact' ? lab('method.exact') : t(`panel.${c.kind}`);
        return `${name} ${v === null ? '—' : formatNumber(v, 1)}`;
      });
      this.readout.textContent = t('profile.readout', { x, y, values: values.join(' · ') });
    }
  }
}
