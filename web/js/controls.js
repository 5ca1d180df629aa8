// The control groups under the panels, built from short declarations. Each
// control reads and writes one part of the state through `get`/`set`, and
// `refresh()` brings every control back in line with the state (after a
// preset, a reset, a drag on a panel or a link).
import { t } from './i18n.js';
import { el, put } from './dom.js';

let uid = 0;
const nextId = (name) => `c-${name}-${++uid}`;

const toHex = (c) => `#${c.map((v) => Math.round(v).toString(16).padStart(2, '0')).join('')}`;
const fromHex = (h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16));

/** Builds controls into fieldsets; `changed(what)` is called after each user change. */
export class Controls {
  constructor(form, changed) {
    this.form = form;
    this.changed = changed;
    this.refreshers = [];
  }

  refresh() {
    for (const r of this.refreshers) r();
  }

  /** Runs `f` on every refresh (a part of the form that rebuilds itself). */
  onRefresh(f) {
    this.refreshers.push(f);
  }

  group(key, name) {
    const fs = el('fieldset', { 'data-group': name }, [el('legend', { text: t(key) })]);
    this.form.append(fs);
    return fs;
  }

  /** A group of controls outside the form (in the side panel): a plain container. */
  section(parent, name) {
    const div = el('div', { class: 'control-section', 'data-group': name });
    parent.append(div);
    return div;
  }

  /** A labelled <select>; `options()` gives [[value, label, disabled?]]. */
  select(parent, { name, label, options, get, set }) {
    const id = nextId(name);
    const select = el('select', { id, name });
    const fill = () => {
      const wanted = options();
      const same = wanted.length === select.options.length && wanted.every(([v, l], i) => select.options[i].value === v && select.options[i].textContent === l);
      if (!same) {
        select.replaceChildren(...wanted.map(([v, l, disabled]) => el('option', { value: v, text: l, disabled: !!disabled })));
      } else {
        wanted.forEach(([, , disabled], i) => put(select.options[i], 'disabled', !!disabled));
      }
      put(select, 'value', get());
    };
    select.addEventListener('change', () => {
      set(select.value);
      this.changed(name);
    });
    this.refreshers.push(fill);
    fill();
    parent.append(el('div', { class: 'row', 'data-control': name }, [el('label', { for: id, text: label }), select]));
    return select;
  }

  /**
   * A slider with a number box beside it, both labelled. The slider spans
   * `min`..`max`; the number box accepts `accept` ([lo, hi], default the
   * slider's span), and a value beyond the slider leaves it at its end.
   */
  range(parent, { name, label, min, max, step, accept, get, set, hint, visible }) {
    const id = nextId(name);
    const value = (v) => (typeof v === 'function' ? v() : v);
    const bounds = () => [value(min), value(max)];
    const accepted = () => (accept ? value(accept) : bounds());
    const range = el('input', { type: 'range', id, name, step: String(step) });
    const number = el('input', { type: 'number', step: String(step), 'aria-label': t('control.number', { label }) });
    const hintEl = hint ? el('p', { class: 'hint' }) : null;
    const row = el('div', { class: 'row', 'data-control': name }, [el('label', { for: id, text: label }), el('div', { class: 'pair' }, [range, number])]);
    const apply = (input) => {
      const [lo, hi] = input === number ? accepted() : bounds();
      let v = Number(input.value);
      if (input.value === '' || !Number.isFinite(v)) return;
      v = Math.min(hi, Math.max(lo, v));
      set(v);
      this.changed(name);
      sync(input);
    };
    const sync = (except) => {
      const [lo, hi] = bounds();
      const [alo, ahi] = accepted();
      put(range, 'min', String(lo));
      put(range, 'max', String(hi));
      put(number, 'min', String(alo));
      put(number, 'max', String(ahi));
      for (const input of [range, number]) {
        if (input !== except) put(input, 'value', String(get()));
      }
      if (hintEl) put(hintEl, 'textContent', hint());
      if (visible) {
        const show = visible();
        put(row, 'hidden', !show);
        if (hintEl) put(hintEl, 'hidden', !show);
      }
    };
    range.addEventListener('input', () => apply(range));
    number.addEventListener('change', () => apply(number));
    this.refreshers.push(() => sync(null));
    sync(null);
    parent.append(row);
    if (hintEl) parent.append(hintEl);
    return range;
  }

  /** Three 0–255 boxes and a colour picker. */
  rgb(parent, { name, label, get, set }) {
    const id = nextId(name);
    const boxes = ['color.r', 'color.g', 'color.b'].map((k, i) => {
      const bid = i === 0 ? id : nextId(name);
      const input = el('input', { type: 'number', id: bid, min: '0', max: '255', step: '1', 'aria-label': `${label}: ${t(k)}` });
      input.addEventListener('change', () => {
        const v = Math.round(Number(input.value));
        if (input.value === '' || !Number.isFinite(v)) return;
        const c = [...get()];
        c[i] = Math.min(255, Math.max(0, v));
        set(c);
        this.changed(name);
        sync();
      });
      return input;
    });
    const picker = el('input', { type: 'color', 'aria-label': t('color.picker', { what: label }) });
    picker.addEventListener('input', () => {
      set(fromHex(picker.value));
      this.changed(name);
      sync();
    });
    const sync = () => {
      const c = get();
      boxes.forEach((b, i) => {
        if (document.activeElement !== b) put(b, 'value', String(c[i]));
      });
      put(picker, 'value', toHex(c));
    };
    this.refreshers.push(sync);
    sync();
    const letters = ['color.r', 'color.g', 'color.b'];
    const rgbEl = el('div', { class: 'rgb' });
    boxes.forEach((b, i) => rgbEl.append(el('span', { 'aria-hidden': 'true', class: 'hint', text: t(letters[i]) }), b));
    rgbEl.append(picker);
    parent.append(el('div', { class: 'row rgb-row', 'data-control': name }, [el('label', { for: id, text: label }), rgbEl]));
  }

  /** Three number boxes (x, y, z). */
  vec3(parent, { name, label, labels, step, get, set }) {
    const id = nextId(name);
    const boxes = labels.map((l, i) => {
      const input = el('input', { type: 'number', id: i === 0 ? id : nextId(name), step: String(step), 'aria-label': `${label}: ${l}` });
      input.addEventListener('change', () => {
        const v = Number(input.value);
        if (input.value === '' || !Number.isFinite(v)) return;
        const p = [...get()];
        p[i] = Math.min(1000, Math.max(-1000, v));
        set(p);
        this.changed(name);
      });
      return input;
    });
    const sync = () => boxes.forEach((b, i) => {
      const v = get()[i];
      if (document.activeElement !== b) put(b, 'value', v === null ? '' : String(Number(v.toFixed(3))));
    });
    this.refreshers.push(sync);
    sync();
    const vecEl = el('div', { class: 'vec' });
    boxes.forEach((b, i) => vecEl.append(el('span', { 'aria-hidden': 'true', class: 'hint', text: labels[i] }), b));
    parent.append(el('div', { class: 'row' }, [el('label', { for: id, text: label }), vecEl]));
  }

  checkbox(parent, { name, label, get, set, disabled }) {
    const id = nextId(name);
    const box = el('input', { type: 'checkbox', id, name });
    box.addEventListener('change', () => {
      set(box.checked);
      this.changed(name);
    });
    const sync = () => {
      put(box, 'checked', get());
      if (disabled) put(box, 'disabled', disabled());
    };
    this.refreshers.push(sync);
    sync();
    parent.append(el('div', { class: 'row check', 'data-control': name }, [box, el('label', { for: id, text: label })]));
    return box;
  }

  button(parent, { label, onclick, id }) {
    const b = el('button', { type: 'button', text: label });
    if (id) b.id = id;
    b.addEventListener('click', onclick);
    parent.append(el('div', { class: 'row' }, [b]));
    return b;
  }

  /**
   * A file picker: a button in the page's language that opens the browser's
   * file dialog (the input itself would speak the browser's language).
   */
  file(parent, { name, label, accept, hint, onfile }) {
    const id = nextId(name);
    const input = el('input', { type: 'file', id, name, accept, class: 'visually-hidden', tabindex: '-1', 'aria-label': label });
    input.addEventListener('change', () => {
      if (input.files.length) onfile(input.files[0]);
      input.value = '';
    });
    const button = el('button', { type: 'button', text: label });
    button.addEventListener('click', () => input.click());
    parent.append(el('div', { class: 'row file-row' }, [button, input]));
    parent.append(el('p', { class: 'hint', text: hint }));
    return input;
  }

  /** An explanation folded under a summary; `text()` fills it on refresh. */
  details(parent, { summary, text }) {
    const body = el('p', { class: 'explain' });
    const d = el('details', { class: 'explain' }, [el('summary', { text: summary }), body]);
    const sync = () => put(body, 'textContent', text());
    this.refreshers.push(sync);
    sync();
    parent.append(d);
    return d;
  }

  /** A line of text that `text()` fills on refresh. */
  note(parent, text) {
    const p = el('p', { class: 'hint' });
    const sync = () => {
      const s = text();
      put(p, 'textContent', s);
      put(p, 'hidden', !s);
    };
    this.refreshers.push(sync);
    sync();
    parent.append(p);
    return p;
  }
}
