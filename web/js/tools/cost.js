// Cost made visible: per method, the render time and how often the
// reflection model was evaluated — once per polygon (flat), per vertex
// (Gouraud) or per pixel (Phong) — from each panel's frames; and a
// measurement on demand, the median of several frames rendered one method
// at a time (so that the three do not share the processor). Every sentence
// under the table is made from the numbers in it, so that it says only
// what they show.
import { t, plural, formatNumber, formatCount } from '../i18n.js';
import { el } from '../dom.js';

const RUNS = 9;
/** Frames rendered first and not counted: the engine's buffers and the browser's compiler settle. */
const WARMUP = 2;
/** Recent frames whose median time the table shows. */
const RECENT = 30;
const GRANULARITY = { flat: 'per_polygon', gouraud: 'per_vertex', phong: 'per_pixel' };

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

export class CostTool {
  constructor(page) {
    this.page = page;
    this.measured = null;
    this.measuring = false;
  }

  build(section) {
    section.append(el('h2', { text: t('tab.cost') }));
    section.append(el('p', { class: 'lead', text: t('cost.lead') }));
    this.table = el('div', { class: 'cost-table' });
    this.button = el('button', { type: 'button', text: t('cost.measure', { runs: RUNS }) });
    this.button.addEventListener('click', () => this.measure());
    this.status = el('p', { class: 'hint', 'aria-live': 'polite' });
    section.append(this.table, el('div', { class: 'row' }, [this.button]), this.status);
    this.update();
  }

  refresh() {}

  /** Renders each method `RUNS` times, one panel after the other, and shows the medians. */
  async measure() {
    if (this.measuring) return;
    this.measuring = true;
    this.button.disabled = true;
    this.status.textContent = t('cost.measuring');
    const results = {};
    try {
      for (const p of this.page.panels) {
        const reply = await p.ask({ type: 'cost', scene: this.page.sceneFor(p.method), runs: RUNS, warmup: WARMUP });
        results[p.method] = { median: median(reply.times), min: Math.min(...reply.times), runs: reply.times.length };
      }
      this.measured = { results, scene: this.page.panels.map((p) => this.page.sceneFor(p.method)).join('\n') };
      this.status.textContent = '';
    } catch (error) {
      this.status.textContent = t('error.instrument', { message: error.message });
    } finally {
      this.measuring = false;
      this.button.disabled = false;
      // The measurement drew plain frames: draw the panels as they were.
      this.page.rerender();
    }
    this.update();
  }

  update() {
    if (!this.table) return;
    const panels = this.page.panels;
    if (!panels.every((p) => p.last)) return;
    const current = panels.map((p) => this.page.sceneFor(p.method)).join('\n');
    const measured = this.measured?.scene === current ? this.measured.results : null;
    const rows = panels.map((p) => {
      const f = p.last;
      const times = p.times.slice(-RECENT);
      const evaluations = f.stats.lighting_evaluations;
      return { method: p.method, time: measured ? measured[p.method].median : median(times), min: measured?.[p.method].min, evaluations, f };
    });
    const most = Math.max(1, ...rows.map((r) => r.evaluations));
    const slowest = Math.max(1e-6, ...rows.map((r) => r.time));
    const head = el('tr', {}, [
      el('th', { scope: 'col', text: t('cost.method') }),
      el('th', { scope: 'col', text: t('cost.timeHead') }),
      el('th', { scope: 'col', text: t('cost.evaluations') }),
    ]);
    const where = (r) => {
      const s = r.f.stats;
      if (r.method === 'flat') return t('cost.per_polygon', { polygons: plural('count.polygonsDrawn', s.rasterized) });
      if (r.method === 'phong') return t('cost.per_pixel', { pixels: plural('count.pixelsShaded', s.fragments_shaded) });
      return t(`cost.per_vertex.${r.f.rasterizer}`);
    };
    const body = rows.map((r) => el('tr', { 'data-method': r.method }, [
      el('th', { scope: 'row', text: t(`panel.${r.method}`) }),
      el('td', { class: 'time' }, [
        el('span', { class: 'num', text: formatNumber(r.time, 1) }),
        r.min !== undefined ? el('span', { class: 'hint', text: ` (${t('cost.min', { ms: formatNumber(r.min, 1) })})` }) : null,
        el('span', { class: 'bar bar-time', style: { width: `${(100 * r.time) / slowest}%` } }),
      ]),
      el('td', { class: 'evaluations' }, [
        el('span', { class: 'num', text: formatCount(r.evaluations) }),
        el('span', { class: 'bar bar-evaluations', style: { width: `${(100 * r.evaluations) / most}%` } }),
        el('span', { class: 'where hint', text: where(r) }),
      ]),
    ]));
    const [flat, gouraud, phong] = rows;
    const ratio = (a, b) => formatNumber(a / Math.max(b, 1e-9), 1);
    const f = flat.f;
    const recent = Math.min(RECENT, ...panels.map((p) => p.times.length));
    const ps = phong.f.stats;
    const sentences = [
      ['cost.time', measured ? t('cost.timeMeasured', { runs: RUNS, warmup: WARMUP }) : plural('cost.timeRecent', recent)],
      flat.evaluations > 0 && ['cost.evaluationRatio', t('cost.evaluationRatio', { gouraud: ratio(gouraud.evaluations, flat.evaluations), phong: ratio(phong.evaluations, flat.evaluations) })],
      flat.time > 0 && ['cost.timeRatio', t('cost.timeRatio', { gouraud: ratio(gouraud.time, flat.time), phong: ratio(phong.time, flat.time) })],
      ['cost.overdraw', t(ps.fragments_shaded > ps.covered_pixels ? 'cost.overdraw.some' : 'cost.overdraw.none', {
        fragments: plural('count.pixelsShaded', ps.fragments_shaded), covered: plural('count.pixelsCovered', ps.covered_pixels),
      })],
      ['cost.frame', t('cost.frame', { polygons: plural('count.polygonsDrawn', f.stats.rasterized), culled: formatCount(f.stats.culled), rasterizer: t(`panel.raster.${f.rasterizer}`) })],
    ].filter(Boolean);
    this.table.replaceChildren(
      el('table', {}, [el('thead', {}, [head]), el('tbody', {}, body)]),
      ...sentences.map(([key, text]) => el('p', { class: 'hint', 'data-sentence': key, text })),
    );
  }
}
