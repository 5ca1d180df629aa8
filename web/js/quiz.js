// The quiz, for a class: the three panels without their names, in a
// shuffled order under the letters A, B, C, and questions a student answers
// by looking — which one is Gouraud shading, which one is Phong's when
// Gouraud has its highlight too, where the Mach bands are (a click on the
// spot), which panel's vertex normals are weighted by area — each answer
// followed by why. A round is the questions in turn, then the score.
//
// Each question sets the scenes the panels draw (the page's own settings
// stay as they were and come back after the quiz): `sceneFor(method)` gives
// a panel's scene while the quiz runs. A click on the Mach-band question is
// right when a polygon edge the Gouraud panel's scanline walk crosses lies
// within REACH pixels of it, on the row clicked (the profile instrument's
// edges, computed by the panel's worker).
import { t, lab } from './i18n.js';
import { el } from './dom.js';
import { sceneToml, defaultState, METHODS } from './state.js';

const LETTERS = ['A', 'B', 'C'];
/** A click this near (image pixels, along its row) to a polygon edge finds the Mach bands. */
export const REACH = 6;

/** The settings each question shows, over the page's defaults. */
const SCENES = {
  which: { model: 'sphere', detail: 12, camera: { yaw: 20, pitch: 15, zoom: 1 } },
  phong: { model: 'sphere', detail: 10, gouraudSpecular: true, camera: { yaw: -25, pitch: 20, zoom: 1 } },
  mach: {
    model: 'sphere', detail: 8, interpolation: 'screen',
    material: { ka: [200, 200, 200], kd: [200, 200, 200], ks: [0, 0, 0], shininess: 1 },
    camera: { yaw: 10, pitch: 10, zoom: 1 },
  },
  normals: { model: 'cylinder', detail: 12, crease: 180, camera: { yaw: 30, pitch: 35, zoom: 1 } },
};

/** The questions of a round, in order. */
export const QUESTIONS = [
  { id: 'gouraud', scene: 'which', kind: 'pick', answer: 'gouraud' },
  { id: 'phong', scene: 'phong', kind: 'pick', answer: 'phong' },
  { id: 'mach', scene: 'mach', kind: 'spot', method: 'gouraud' },
  { id: 'normals', scene: 'normals', kind: 'pick', answer: 'area', weightings: ['uniform', 'area', 'angle'] },
];

function shuffled(items, random) {
  const a = [...items];
  for (let i = a.length - 1; i > 0; i--) {
    const j = Math.floor(random() * (i + 1));
    [a[i], a[j]] = [a[j], a[i]];
  }
  return a;
}

export class Quiz {
  /** `page`: state(), size(), panels, changed(), ask(method, request). */
  constructor(page) {
    this.page = page;
    this.on = false;
    this.box = document.querySelector('#quiz-box');
    this.random = Math.random;
  }

  /** Starts a round (or ends the quiz). */
  toggle(on = !this.on) {
    this.on = on;
    document.body.classList.toggle('quizzing', on);
    document.querySelector('#quiz').setAttribute('aria-pressed', String(on));
    this.box.hidden = !on;
    if (on) this.start();
    else {
      for (const p of this.page.panels) {
        p.figure.style.removeProperty('order');
        p.figure.removeAttribute('data-letter');
      }
      this.page.changed();
    }
  }

  start() {
    this.index = 0;
    this.score = 0;
    this.#ask();
  }

  /** The current question. */
  get question() {
    return QUESTIONS[this.index];
  }

  #ask() {
    const q = this.question;
    this.answered = null;
    // Which panel stands under which letter: the methods (or, for the normals,
    // the weightings) shuffled.
    this.order = shuffled(METHODS, this.random);
    this.weightings = q.weightings ? shuffled(q.weightings, this.random) : null;
    this.order.forEach((method, k) => {
      const panel = this.page.panels.find((p) => p.method === method);
      panel.figure.style.setProperty('order', String(k));
      panel.figure.dataset.letter = LETTERS[k];
    });
    this.page.changed();
    this.draw();
  }

  /** The scene the panel of `method` draws for the current question. */
  sceneFor(method) {
    const q = this.question;
    const state = { ...defaultState(), ...structuredClone(SCENES[q.scene]), size: this.page.size() };
    if (q.weightings) {
      // Every panel draws Phong shading; what differs is the weighting.
      const k = this.order.indexOf(method);
      return sceneToml({ ...state, normals: this.weightings[k] }, 'phong');
    }
    return sceneToml(state, method);
  }

  /** The letter of the panel that is the right answer. */
  rightLetter() {
    const q = this.question;
    const k = q.weightings ? this.weightings.indexOf(q.answer) : this.order.indexOf(q.answer ?? q.method);
    return LETTERS[k];
  }

  /** The answer `letter` (A, B, C) to a question that asks to pick a panel. */
  pick(letter) {
    if (this.answered || this.question.kind !== 'pick') return;
    this.#answer(letter === this.rightLetter(), { letter });
  }

  /** A click on a panel: the pick of its letter, or the spot asked for. */
  clickPanel(method, x, y) {
    if (this.index >= QUESTIONS.length) return;
    if (this.question.kind === 'pick') this.pick(LETTERS[this.order.indexOf(method)]);
    else this.spot(method, x, y);
  }

  /** A click on pixel (x, y) of the panel of `method`: the spot question's answer. */
  async spot(method, x, y) {
    const q = this.question;
    if (this.answered || q.kind !== 'spot') return false;
    if (method !== q.method) {
      this.#answer(false, { wrongPanel: true });
      return true;
    }
    const reply = await this.page.ask(method, { type: 'profile', scene: this.sceneFor(method), row: y });
    const curve = reply.profile.curves.find((c) => c.kind === 'gouraud');
    const near = curve.polygon_edges.map((k) => Math.abs(reply.profile.pixels[k][0] + 0.5 - x)).sort((a, b) => a - b)[0];
    this.#answer(near !== undefined && near <= REACH, { x, y, near });
    return true;
  }

  #answer(right, detail) {
    this.answered = { right, ...detail };
    if (right) this.score += 1;
    this.draw();
  }

  next() {
    if (this.index + 1 < QUESTIONS.length) {
      this.index += 1;
      this.#ask();
    } else {
      this.index = QUESTIONS.length;
      this.draw();
    }
  }

  /** Shows the question, its answers and, once answered, why. */
  draw() {
    const box = this.box;
    box.replaceChildren();
    if (!this.on) return;
    box.append(el('h2', { text: t('quiz.heading') }));
    if (this.index >= QUESTIONS.length) {
      box.append(el('p', { class: 'quiz-score', text: t('quiz.score', { right: this.score, total: QUESTIONS.length }) }));
      const again = el('button', { type: 'button', text: t('quiz.again') });
      again.addEventListener('click', () => this.start());
      const done = el('button', { type: 'button', text: t('quiz.end') });
      done.addEventListener('click', () => this.toggle(false));
      box.append(el('div', { class: 'quiz-answers' }, [again, done]));
      return;
    }
    const q = this.question;
    box.append(el('p', { class: 'quiz-progress', text: t('quiz.progress', { n: this.index + 1, total: QUESTIONS.length }) }));
    const gouraudLetter = LETTERS[this.order.indexOf('gouraud')];
    box.append(el('p', { class: 'quiz-question', text: t(`quiz.${q.id}.question`, { letter: gouraudLetter }) }));
    if (q.kind === 'pick') {
      const answers = el('div', { class: 'quiz-answers', role: 'group', 'aria-label': t('quiz.answers') });
      for (const letter of LETTERS) {
        const b = el('button', { type: 'button', class: 'quiz-answer', 'data-letter': letter, text: t('quiz.panel', { letter }) });
        b.disabled = !!this.answered;
        if (this.answered && letter === this.rightLetter()) b.classList.add('right');
        if (this.answered && letter === this.answered.letter && !this.answered.right) b.classList.add('wrong');
        b.addEventListener('click', () => this.pick(letter));
        answers.append(b);
      }
      box.append(answers);
    } else {
      box.append(el('p', { class: 'hint', text: t('quiz.mach.how', { letter: gouraudLetter }) }));
    }
    if (this.answered) {
      const a = this.answered;
      let verdict;
      if (q.kind === 'pick') verdict = a.right ? t('quiz.right') : t('quiz.wrong', { letter: this.rightLetter() });
      else if (a.wrongPanel) verdict = t('quiz.mach.wrongPanel', { letter: gouraudLetter });
      else verdict = a.right ? t('quiz.right') : t('quiz.mach.missed');
      box.append(
        el('p', { class: `quiz-verdict ${a.right ? 'right' : 'wrong'}`, text: verdict }),
        el('p', { class: 'quiz-why', text: t(`quiz.${q.id}.why`) }),
      );
      // The method's own explanation, as the Methods tab gives it.
      const more = { gouraud: 'about.gouraud', phong: 'about.phong', mach: 'about.mach_bands' }[q.id];
      if (more) box.append(el('p', { class: 'quiz-why hint', text: lab(more) }));
      const next = el('button', { type: 'button', class: 'quiz-next', text: this.index + 1 < QUESTIONS.length ? t('quiz.next') : t('quiz.finish') });
      next.addEventListener('click', () => this.next());
      box.append(next);
    }
  }
}
