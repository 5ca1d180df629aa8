// Overlays: the mesh's structure drawn over the panels — wireframe, face
// normals, vertex normals, the light — on all panels or on each. The
// panels' workers draw them (shadelab-lab's `draw_overlays`, as
// `shadelab render --overlay` does), hidden where the model is in front.
import { t, lab } from '../i18n.js';
import { el } from '../dom.js';
import { METHODS, OVERLAYS } from '../state.js';

/** The overlays' colours (shadelab-lab: WIREFRAME, FACE_NORMAL, VERTEX_NORMAL, LIGHT). */
export const OVERLAY_COLORS = {
  wireframe: [255, 230, 90],
  'face-normals': [80, 220, 255],
  'vertex-normals': [120, 255, 120],
  light: [255, 255, 255],
};

export class OverlaysTool {
  constructor(page) {
    this.page = page;
    this.boxes = [];
  }

  build(section) {
    const page = this.page;
    section.append(el('h2', { text: t('tab.overlays') }));
    section.append(el('p', { class: 'lead', text: lab('about.overlays') }));
    const columns = ['all', ...METHODS];
    const head = el('tr', {}, [el('th', { scope: 'col', text: t('overlays.what') }), ...columns.map((c) => el('th', { scope: 'col', text: c === 'all' ? t('overlays.all') : t(`panel.${c}`) }))]);
    this.boxes = [];
    const rows = OVERLAYS.map((name) => {
      const [r, g, b] = OVERLAY_COLORS[name];
      const label = t(`overlays.${name}`);
      const cells = columns.map((column) => {
        const box = el('input', {
          type: 'checkbox',
          'data-overlay': name,
          'data-panel': column,
          'aria-label': t('overlays.toggle', { what: label, where: column === 'all' ? t('overlays.onAll') : t(`panel.${column}`) }),
        });
        box.addEventListener('change', () => {
          const st = page.state();
          for (const m of column === 'all' ? METHODS : [column]) {
            const set = new Set(st.overlays[m]);
            if (box.checked) set.add(name);
            else set.delete(name);
            st.overlays[m] = OVERLAYS.filter((n) => set.has(n));
          }
          page.changed();
        });
        this.boxes.push(box);
        return el('td', {}, [box]);
      });
      return el('tr', {}, [
        el('th', { scope: 'row' }, [el('span', { class: 'swatch', style: { background: `rgb(${r}, ${g}, ${b})` }, 'aria-hidden': 'true' }), el('span', { text: label })]),
        ...cells,
      ]);
    });
    section.append(el('table', { class: 'overlay-grid' }, [el('thead', {}, [head]), el('tbody', {}, rows)]));
    section.append(el('p', { class: 'hint', text: t('overlays.hint') }));
    this.refresh();
  }

  refresh() {
    const st = this.page.state();
    for (const box of this.boxes) {
      const name = box.dataset.overlay;
      const panel = box.dataset.panel;
      const on = METHODS.map((m) => st.overlays[m].includes(name));
      if (panel === 'all') {
        box.checked = on.every(Boolean);
        box.indeterminate = !box.checked && on.some(Boolean);
      } else {
        box.checked = st.overlays[panel].includes(name);
      }
    }
  }

  update() {}
}
