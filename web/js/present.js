// Presenting, for a lecture hall: the panels as large as the screen allows,
// each drawn at the screen's own pixels (the canvas as many pixels wide as
// the panel is wide on the screen, times the device pixel ratio: no
// browser scaling, no blur), and a bar with the few controls a lecture
// needs — the model, what a drag moves, the shading options — while the
// keyboard keeps working on the panels. Esc (or the bar's button) ends it.
import { t } from './i18n.js';
import { el } from './dom.js';
import { Controls } from './controls.js';
import { param } from './params.js';
import { paramControl } from './form.js';

export class Present {
  /** `page`: state(), models(), modelName(name), dragMode get/set, changed(), visiblePanels(). */
  constructor(page) {
    this.page = page;
    this.on = false;
    this.bar = document.querySelector('#present-bar');
    this.side = 0;
    this.dpr = 1;
    this.observer = new ResizeObserver(() => this.on && this.layout());
    window.addEventListener('keydown', (e) => {
      if (this.on && e.key === 'Escape') this.toggle(false);
    });
  }

  /** The bar's controls, in the current language. */
  build() {
    const page = this.page;
    const s = page.state;
    this.bar.replaceChildren();
    const c = new Controls(this.bar, page.changed);
    this.controls = c;
    c.select(this.bar, {
      name: 'present-model', label: t('model.source'),
      options: () => page.models().map((m) => [m.name, page.modelName(m.name)]).concat(page.userFile() ? [[page.userFile().name, page.userFile().name]] : []),
      get: () => s().model,
      set: (v) => page.setModel(v, false),
    });
    c.select(this.bar, {
      name: 'present-drag', label: t('camera.drag'),
      options: () => ['camera', 'light'].map((v) => [v, t(`camera.drag.${v}`)]),
      get: () => page.dragMode(), set: (v) => page.setDragMode(v),
    });
    // The shading options, as the column has them (form.js).
    for (const name of ['material.shininess', 'gouraudSpecular', 'specular', 'interpolation']) {
      paramControl(c, this.bar, param(name), { of: s, prefix: 'present' });
    }
    const done = el('button', { type: 'button', class: 'present-exit', text: t('present.exit') });
    done.addEventListener('click', () => this.toggle(false));
    this.bar.append(done);
  }

  refresh() {
    this.controls?.refresh();
  }

  /** Starts or ends presenting. */
  toggle(on = !this.on) {
    this.on = on;
    document.body.classList.toggle('presenting', on);
    document.querySelector('#present').setAttribute('aria-pressed', String(on));
    this.bar.hidden = !on;
    if (on) {
      this.build();
      this.observer.observe(document.documentElement);
      this.layout();
      // The keyboard works at once: arrows orbit, + and − zoom.
      this.page.visiblePanels()[0]?.canvas.focus({ preventScroll: true });
    } else {
      this.observer.disconnect();
      document.body.style.removeProperty('--present-side');
      this.side = 0;
      this.page.changed();
    }
  }

  /**
   * The panels' side in CSS pixels: the largest that fits the window's
   * width and, with the captions and the bar, its height; then the frames
   * are asked for at that side times the device pixel ratio.
   */
  layout() {
    const panels = this.page.visiblePanels();
    const n = panels.length;
    const figure = panels[0].figure;
    const style = getComputedStyle(figure);
    const pad = parseFloat(style.paddingLeft) + parseFloat(style.paddingRight) + parseFloat(style.borderLeftWidth) + parseFloat(style.borderRightWidth);
    const gap = parseFloat(getComputedStyle(document.querySelector('#panels')).columnGap) || 0;
    const stageStyle = getComputedStyle(document.querySelector('.stage'));
    const sum = (...keys) => keys.reduce((a, k) => a + (parseFloat(stageStyle[k]) || 0), 0);
    const width = window.innerWidth - sum('paddingLeft', 'paddingRight');
    document.body.style.setProperty('--present-count', String(n));
    let side = this.side || 480;
    // The captions' height depends on the side (they wrap): fit, measure, fit again.
    for (let pass = 0; pass < 3; pass++) {
      document.body.style.setProperty('--present-side', `${side}px`);
      const chrome = figure.offsetHeight - figure.querySelector('.view').offsetHeight;
      const height = window.innerHeight - sum('paddingTop', 'paddingBottom', 'rowGap') - this.bar.offsetHeight;
      const fit = Math.floor(Math.max(64, Math.min((width - (n - 1) * gap) / n - pad, height - chrome - 2)));
      if (fit === side) break;
      side = fit;
    }
    document.body.style.setProperty('--present-side', `${side}px`);
    const dpr = window.devicePixelRatio || 1;
    if (side !== this.side || dpr !== this.dpr) {
      this.side = side;
      this.dpr = dpr;
      this.page.changed();
    }
  }

  /** The size the panels are drawn at while presenting (device pixels), or null. */
  renderSize() {
    return this.on && this.side ? Math.round(this.side * this.dpr) : null;
  }
}
