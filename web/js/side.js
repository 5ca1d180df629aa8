// The side panel beside the three panels: one tab per instrument. Each
// instrument is an object with `build(section)` (its controls and views,
// built again when the language changes), `refresh()` (controls back in line
// with the state) and `update()` (recompute what it shows, on demand: only
// the open tab's instrument computes, and only once the panels are still).
import { t } from './i18n.js';
import { el } from './dom.js';
import { About } from './tools/about.js';
import { Inspector } from './tools/inspector.js';
import { ProfileTool } from './tools/profile.js';
import { ErrorsTool } from './tools/errors.js';
import { OverlaysTool } from './tools/overlays.js';
import { QuadTool } from './tools/quad.js';
import { CostTool } from './tools/cost.js';

export class Side {
  constructor(aside, page) {
    this.aside = aside;
    this.page = page;
    this.tools = {
      about: new About(page),
      inspector: new Inspector(page),
      profile: new ProfileTool(page),
      errors: new ErrorsTool(page),
      overlays: new OverlaysTool(page),
      quad: new QuadTool(page),
      cost: new CostTool(page),
    };
  }

  /** Builds the tabs and every instrument in the current language. */
  build() {
    const tablist = el('div', { class: 'tabs', role: 'tablist', 'aria-label': t('side.label') });
    this.buttons = {};
    this.sections = {};
    const body = [];
    for (const name of Object.keys(this.tools)) {
      const button = el('button', {
        type: 'button', role: 'tab', id: `tab-${name}`, 'aria-controls': `tool-${name}`,
        'data-tab': name, text: t(`tab.${name}`),
      });
      button.addEventListener('click', () => this.page.setTab(name));
      button.addEventListener('keydown', (e) => this.#arrows(e, name));
      tablist.append(button);
      this.buttons[name] = button;
      const section = el('section', { class: 'tool', id: `tool-${name}`, role: 'tabpanel', 'aria-labelledby': `tab-${name}`, 'data-tool': name });
      this.sections[name] = section;
      this.tools[name].build(section);
      body.push(section);
    }
    this.aside.replaceChildren(tablist, ...body);
    this.aside.hidden = false;
    this.show();
  }

  #arrows(e, name) {
    const names = Object.keys(this.tools);
    const k = names.indexOf(name);
    const to = { ArrowRight: k + 1, ArrowDown: k + 1, ArrowLeft: k - 1, ArrowUp: k - 1, Home: 0, End: names.length - 1 }[e.key];
    if (to === undefined) return;
    e.preventDefault();
    const next = names[(to + names.length) % names.length];
    this.page.setTab(next);
    this.buttons[next].focus();
  }

  /** Shows the open tab. */
  show() {
    const open = this.page.view.tab;
    for (const [name, button] of Object.entries(this.buttons)) {
      const on = name === open;
      button.setAttribute('aria-selected', String(on));
      button.tabIndex = on ? 0 : -1;
      this.sections[name].hidden = !on;
    }
  }

  /** Every instrument's controls back in line with the state. */
  refresh() {
    for (const tool of Object.values(this.tools)) tool.refresh();
  }

  /** The open instrument recomputes what it shows, if anything changed. */
  update() {
    return this.tools[this.page.view.tab].update();
  }
}
