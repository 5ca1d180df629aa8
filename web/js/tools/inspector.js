// The pixel inspector: for the chosen pixel, what each panel's method did
// there, with the textbook's formulas filled in. Each panel's worker
// inspects its own method (shadelab-lab's `inspect`, the same text as
// `shadelab explain`); the page lays the lines out and marks the polygon,
// the scanline and P and Q on the panels.
import { t, lab, language } from '../i18n.js';
import { el } from '../dom.js';
import { Controls } from '../controls.js';

/** A line that is a formula or a vector, not a sentence: set it in monospace. */
const FORMULA = /^(?:[A-Za-z]{1,2}(?:_[A-Za-z]+)?|r|h|l|n) = /;

export class Inspector {
  constructor(page) {
    this.page = page;
    this.key = '';
    this.answer = null;
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
    for (const m of a.methods) {
      const lines = m.text.trimEnd().split('\n');
      const title = lines.shift().replace(/^== /, '');
      const [r, g, b] = m.color;
      const article = el('article', { class: 'inspect-method', 'data-method': m.method }, [
        el('h3', {}, [
          el('span', { class: 'swatch', style: { background: `rgb(${r}, ${g}, ${b})` }, 'aria-hidden': 'true' }),
          el('span', { text: title }),
        ]),
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
      out.append(article);
    }
    for (const p of this.page.panels) {
      const m = a.methods.find((q) => q.method === p.method);
      p.marks.set({ inspection: m && m.covered ? m : null });
    }
  }
}
