// The browser tests' handle on the page, `window.shadelab`: set only when
// the test sets `globalThis.SHADELAB_TEST_HOOKS = true` before the page's
// scripts run (Playwright's `addInitScript`); a plain page exposes nothing.
import { language } from './i18n.js';
import { paint } from './panels.js';

/**
 * Sets `window.shadelab` from `page` (what the form and the instruments see
 * of the page, main.js) and `more`, what only the tests look at: whether
 * the instruments are computing, the side panel, how the panels are drawn
 * together, the scene each panel was asked for, presenting and the quiz.
 */
export function exposeForTests(page, more) {
  const panels = page.panels;
  window.shadelab = {
    get state() { return page.state(); },
    get view() { return page.view; },
    get language() { return language(); },
    panels,
    get exactPanel() { return page.exactPanel; },
    sceneToml: (method) => page.sceneFor(method),
    update(patch) {
      patch(page.state());
      page.changed();
    },
    idle: () => Promise.all(panels.map((p) => p.idle())),
    /** Per panel, how often its engine parsed a file, adopted a mesh, prepared a model, read a scene, drew. */
    counts: async () => Object.fromEntries(await Promise.all(panels.map(async (p) => [p.method, (await p.ask({ type: 'counts' })).counts]))),
    /** Resolves once the panels are still and the open instrument has caught up. */
    async instrumentsIdle() {
      for (;;) {
        await Promise.all(panels.map((p) => p.idle()));
        await new Promise((r) => setTimeout(r, 120));
        if (!more.instrumentsBusy() && panels.every((p) => !p.busy && p.pending === null)) return;
      }
    },
    get inspection() { return more.side().tools.inspector.answer; },
    get profile() { return more.side().tools.profile.data; },
    get quad() { return more.side().tools.quad.data; },
    frameTimes: () => Object.fromEntries(panels.map((p) => [p.method, [...p.times]])),
    /**
     * Whether panels that share a scene are drawn in one request: `auto`
     * (fewer than three cores), true or false; and, when given, by how many
     * workers, each drawing a part of the rows.
     */
    drawTogether: more.drawTogether,
    /** The scene each panel was last asked to draw. */
    panelScene: more.panelScene,
    get present() { return more.present(); },
    get quiz() { return more.quiz(); },
    saveAnimation: more.saveAnimation,
    setModel: page.setModel,
    setTab: page.setTab,
    openFile: page.openFile,
    paint,
  };
}
