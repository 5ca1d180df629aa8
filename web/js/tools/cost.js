// Cost made visible: per method, the render time and how often the
// reflection model was evaluated — once per polygon (flat), per vertex
// (Gouraud) or per pixel (Phong) — from each panel's frames; and a
// measurement on demand, the median of several frames rendered one method
// at a time (so that the three do not share the processor).
import { t, lab, formatNumber, formatCount } from '../i18n.js';
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
    section.append(el('p', { class: 'lead', text: lab('about.cost') }));
    this.table = el('div', { class: 'cost-table' });
    this.button = el('button', { type: 'button', text: t('cost.measure', { runs: RUNS }) });
    this.button.addEventListener('click', () => this.measure());
    this.status = el('p', { class: 'hint', 'aria-live': 'polite' });
    section.append(this.table, el('div', { class: 'row' }, [this.button]), this.status, el('p', { class: 'hint', text: t('cost.note') }));
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
        el('span', { class: 'where hint', text: t(`cost.${GRANULARITY[r.method]}`, { polygons: formatCount(r.f.stats.rasterized), pixels: formatCount(r.f.stats.fragments_shaded) }) }),
      ]),
    ]));
    const f = rows[0].f;
    this.table.replaceChildren(
      el('table', {}, [el('thead', {}, [head]), el('tbody', {}, body)]),
      el('p', { class: 'hint', text: measured ? t('cost.timeMeasured', { runs: RUNS }) : t('cost.time', { frames: RECENT }) }),
      el('p', { class: 'hint', text: t('cost.frame', { polygons: formatCount(f.stats.rasterized), pixels: formatCount(f.stats.fragments_shaded), rasterizer: t(`panel.raster.${f.rasterizer}`) }) }),
    );
  }
}
