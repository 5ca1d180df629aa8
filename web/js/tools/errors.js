// The error map: for the models whose exact surface is known, the panels
// show each method's per-pixel error against it as a heat map (and a fourth
// panel the exact surface), on one colour scale. Each panel's worker
// computes its map with its frame (shadelab-lab's `ErrorMap`, as
// `shadelab errors` does); this tab holds the switch, the scale and the numbers.
import { t, lab, formatNumber, formatCount } from '../i18n.js';
import { el, put } from '../dom.js';
import { Controls } from '../controls.js';
import { hasExactSurface, EXACT_MODELS } from '../state.js';

/** Fixed scales offered beside the automatic one, 0–255 units. */
const SCALES = [5, 10, 20, 25, 50, 100, 200, 255];

/**
 * The automatic scale: the smallest of 1, 2, 2.5, 5 times a power of ten
 * that is at least the largest error (shadelab-lab's `heat_scale`, which
 * `shadelab errors` uses).
 */
export function heatScale(largest) {
  if (!(largest > 0)) return 1;
  const p = 10 ** Math.floor(Math.log10(largest));
  return [1, 2, 2.5, 5, 10].map((m) => m * p).find((c) => c >= largest) ?? 10 * p;
}

export class ErrorsTool {
  constructor(page) {
    this.page = page;
  }

  build(section) {
    const page = this.page;
    const s = page.state;
    section.append(el('h2', { text: t('tab.errors') }));
    section.append(el('details', { class: 'explain' }, [
      el('summary', { text: t('explain.what') }),
      el('p', { text: lab('about.exact') }),
      el('p', { text: lab('about.errors') }),
    ]));
    this.unavailable = el('p', { class: 'note', text: t('errors.unavailable', { models: EXACT_MODELS.map((m) => t(`model.name.${m}`)).join(', ') }) });
    section.append(this.unavailable);
    const box = el('div', { class: 'tool-controls' });
    section.append(box);
    const c = new Controls(box, () => page.changed());
    this.controls = c;
    c.checkbox(box, {
      name: 'errors', label: t('errors.show'),
      get: () => s().errors && hasExactSurface(s()), set: (v) => (s().errors = v),
      disabled: () => !hasExactSurface(s()),
    });
    c.select(box, {
      name: 'error-scale', label: t('errors.scale'),
      options: () => [['auto', t('errors.scale.auto')], ...[...new Set([...SCALES, s().errorScale ?? SCALES[0]])].sort((a, b) => a - b).map((v) => [String(v), `0–${formatNumber(v, v % 1 ? 1 : 0)}`])],
      get: () => (s().errorScale === null ? 'auto' : String(s().errorScale)),
      set: (v) => (s().errorScale = v === 'auto' ? null : Number(v)),
    });
    this.scaleBox = el('div', { class: 'scale' });
    this.table = el('div', { class: 'error-table' });
    section.append(this.scaleBox, this.table);
    this.refresh();
    this.update();
  }

  refresh() {
    if (!this.controls) return;
    this.controls.refresh();
    put(this.unavailable, 'hidden', hasExactSurface(this.page.state()));
  }

  /** Shows the colour scale and each panel's numbers (computed with its frame). */
  update() {
    if (!this.table) return;
    const page = this.page;
    const frames = page.panels.map((p) => p.last);
    const on = page.errorsShown();
    this.scaleBox.replaceChildren();
    this.table.replaceChildren();
    if (!on) {
      if (hasExactSurface(page.state())) this.table.append(el('p', { class: 'hint', text: t('errors.off') }));
      return;
    }
    if (!frames.every((f) => f?.errors)) return;
    const scale = frames[0].errors.scale;
    // The colour bar, its top the scale's value, with five ticks.
    const bar = page.errorBar;
    if (bar) {
      const canvas = el('canvas', { width: bar.width, height: bar.height, class: 'scale-bar', role: 'img', 'aria-label': lab('plot.error_scale') });
      canvas.getContext('2d').putImageData(new ImageData(bar.pixels, bar.width, bar.height), 0, 0);
      const labels = el('div', { class: 'scale-ticks' }, [0, 1, 2, 3, 4].map((k) =>
        el('span', { style: { top: `${100 - k * 25}%` }, text: formatNumber((scale * k) / 4, scale % 4 ? 1 : 0) })));
      this.scaleBox.append(el('p', { class: 'scale-title', text: lab('plot.error_scale') }), el('div', { class: 'scale-body' }, [canvas, labels]),
        el('p', { class: 'hint', text: t('errors.grey') }));
    }
    const head = el('tr', {}, ['errors.method', 'errors.mean', 'errors.max', 'errors.at'].map((k) => el('th', { scope: 'col', text: t(k) })));
    const rows = page.panels.map((p) => {
      const e = p.last.errors;
      const at = e.max_at
        ? el('button', { type: 'button', class: 'link', title: t('errors.inspect'), text: `(${e.max_at[0]}, ${e.max_at[1]})`, onclick: () => page.inspectPixel(...e.max_at) })
        : '—';
      return el('tr', { 'data-method': p.method }, [
        el('th', { scope: 'row', text: t(`panel.${p.method}`) }),
        el('td', { class: 'mean', text: formatNumber(e.mean, 3) }),
        el('td', { class: 'max', text: formatNumber(e.max, 2) }),
        el('td', {}, [at]),
      ]);
    });
    this.table.append(
      el('table', {}, [el('thead', {}, [head]), el('tbody', {}, rows)]),
      el('p', { class: 'hint', text: t('errors.surfaceOnly', { compared: formatCount(frames[0].errors.compared), pixels: formatCount(frames[0].errors.surface_only), meshOnly: formatCount(frames[0].errors.mesh_only) }) }),
    );
  }
}
