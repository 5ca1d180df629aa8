// The quad study: a square with one bright vertex, turned on the screen,
// Gouraud-shaded whole (as the textbook walks a quad) and as two triangles
// (as hardware does); and the value at its centre against the turn.
// shadelab-lab's `quad_study`, as `shadelab quad` draws it.
import { t, lab, formatNumber } from '../i18n.js';
import { el } from '../dom.js';
import { Controls } from '../controls.js';
import { paint } from '../panels.js';
import { drawPlot } from '../plot.js';

/** The study's image: odd, so that a pixel centre is the square's centre. */
const SIZE = 121;
/** The turns the curve is drawn at. */
const CURVE = Array.from({ length: 46 }, (_, k) => 2 * k);
const COLORS = { whole: '#f5a623', fans: '#4fb3ff' };

export class QuadTool {
  constructor(page) {
    this.page = page;
    this.key = '';
    this.data = null;
    this.curve = null;
  }

  build(section) {
    const page = this.page;
    const s = page.state;
    section.append(el('h2', { text: t('tab.quad') }));
    section.append(el('details', { class: 'explain' }, [el('summary', { text: t('explain.what') }), el('p', { text: lab('about.quad') })]));
    const box = el('div', { class: 'tool-controls' });
    section.append(box);
    this.controls = new Controls(box, () => page.changed());
    this.controls.range(box, {
      name: 'quad-angle', label: t('quad.angle'), min: 0, max: 90, step: 1,
      get: () => s().quadAngle, set: (v) => (s().quadAngle = v),
    });
    this.canvases = {};
    this.captions = {};
    const pictures = el('div', { class: 'quad-pictures' });
    for (const kind of ['whole', 'fans']) {
      const canvas = el('canvas', { width: SIZE, height: SIZE, class: 'quad-picture', role: 'img', 'aria-label': t(`quad.${kind}`) });
      const caption = el('figcaption', {});
      this.canvases[kind] = canvas;
      this.captions[kind] = caption;
      pictures.append(el('figure', { 'data-kind': kind }, [el('p', { class: 'quad-title', text: t(`quad.${kind}`) }), canvas, caption]));
    }
    this.plotTitle = el('h3', { class: 'plot-title', text: t('quad.curve') });
    this.plot = el('canvas', { class: 'plot plot-quad', role: 'img', 'aria-label': t('quad.curve') });
    this.legend = el('div', { class: 'legend' }, ['whole', 'fans'].map((k) => el('span', { class: 'legend-item' }, [
      el('span', { class: 'key', style: { '--key': COLORS[k] }, 'aria-hidden': 'true' }), el('span', { text: t(`quad.${k}`) }),
    ])));
    section.append(pictures, this.plotTitle, this.legend, this.plot);
    section.append(el('details', { class: 'explain' }, [
      el('summary', { text: t('quad.inPanels') }),
      el('p', { text: lab('about.polygons_whole') }),
      el('p', { text: lab('about.polygons_fans') }),
    ]));
    this.error = el('p', { class: 'tool-error', hidden: true });
    section.append(this.error);
    new ResizeObserver(() => this.#draw()).observe(this.plot);
    this.key = '';
    this.#draw();
  }

  refresh() {
    this.controls?.refresh();
  }

  async update() {
    const angle = this.page.state().quadAngle;
    const key = String(angle);
    if (key === this.key) return;
    this.key = key;
    try {
      const reply = await this.page.panels[0].ask({ type: 'quad', angle, size: SIZE, curve: this.curve ? [] : CURVE });
      if (key !== this.key) return;
      if (!this.curve) this.curve = reply.quad.curve;
      this.data = reply;
      this.error.hidden = true;
    } catch (error) {
      this.error.textContent = t('error.instrument', { message: error.message });
      this.error.hidden = false;
    }
    this.#draw();
  }

  #draw() {
    if (!this.plot || !this.data) return;
    const d = this.data;
    paint(this.canvases.whole, this.canvases.whole.getContext('2d'), d.whole);
    paint(this.canvases.fans, this.canvases.fans.getContext('2d'), d.fans);
    this.captions.whole.textContent = t('quad.centre', { value: formatNumber(d.quad.whole_centre, 3) });
    this.captions.fans.textContent = t('quad.centre', { value: formatNumber(d.quad.fans_centre, 3) });
    const curve = this.curve ?? [];
    drawPlot(this.plot, {
      x: [0, 90], y: [0, 0.75],
      series: [
        { color: COLORS.whole, points: curve.map(([a, w]) => [a, w]) },
        { color: COLORS.fans, points: curve.map(([a, , f]) => [a, f]) },
      ],
      vlines: [{ x: d.quad.angle, color: 'rgba(255, 255, 255, 0.7)', dash: [3, 3] }],
      xLabel: t('quad.angle'),
      yLabel: t('quad.centreAxis'),
    });
  }
}
