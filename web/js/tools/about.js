// The "Methods" tab: what the three methods do and why they look as they
// do, in the words of shadelab-lab's texts, and how to use the instruments.
import { t, lab } from '../i18n.js';
import { el } from '../dom.js';

export class About {
  constructor(page) {
    this.page = page;
  }

  build(section) {
    const topic = (title, ...ids) => [el('h3', { text: title }), ...ids.map((id) => el('p', { text: lab(id) }))];
    section.append(
      el('h2', { text: t('about.heading') }),
      el('p', { class: 'lead', text: t('about.lead') }),
      ...topic(t('about.model'), 'about.reflection_model'),
      ...topic(lab('method.flat'), 'about.flat'),
      ...topic(lab('method.gouraud'), 'about.gouraud'),
      ...topic(lab('method.phong'), 'about.phong'),
      ...topic(t('about.mach'), 'about.mach_bands'),
      ...topic(t('about.interpolation'), 'about.interpolation_screen', 'about.interpolation_perspective'),
      el('h3', { text: t('about.howto') }),
      el('ul', { class: 'howto' }, ['click', 'alt', 'drag', 'tabs', 'link'].map((k) => el('li', { text: t(`about.howto.${k}`) }))),
    );
  }

  refresh() {}

  update() {}
}
