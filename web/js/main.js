// The viewer: three panels (flat | Gouraud | Phong), each rendered by
// shadelab's WebAssembly in its own worker from the same scene file, the
// controls that change that scene, and beside them the instruments that
// explain the pictures. Everything the page knows is in `state` (the scene
// and the instruments' settings) and `view` (language, open tab); every
// change re-renders the three panels and rewrites the link. Instruments
// compute on demand, once the panels are still, so dragging stays fast.
// Presenting (present.js) draws the panels larger; the quiz (quiz.js) gives
// the panels scenes of its own for a while.
import { t, lab, plural, translateDocument, setLanguage, negotiate, LANGUAGE_NAMES } from './i18n.js';
import { Panel, PanelGroup, ImagePanel } from './panels.js';
import { beforeNextPaint, holdPaintWorkWhile } from './dom.js';
import { buildForm, lightSwatch } from './form.js';
import { Side } from './side.js';
import { attachInteraction, attachDrop } from './interaction.js';
import { exportPng, exportScene, saveAnimation as saveOrbit } from './export.js';
import { markerPositions, dragLight, RADIUS } from './lights.js';
import { Present } from './present.js';
import { Quiz } from './quiz.js';
import { exposeForTests } from './testhooks.js';
import { heatScale } from './tools/errors.js';
import {
  METHODS, MAX_FILE_MIB, LANGUAGES,
  defaultState, defaultView, sceneToml, toHash, fromHash, hasExactSurface,
} from './state.js';

const $ = (selector) => document.querySelector(selector);

let state = defaultState();
let view = defaultView();
let models = [];
/** The user's file as loaded into the engines: its summary, or null. */
let userFile = null;
let panels = [];
/** The three panels drawn in one request (see panels.js). */
let group = null;
let exactPanel = null;
let form = null;
let side = null;
let dragMode = 'camera';
/** The light that Shift+drag and the arrow keys with Shift move: the last one touched. */
let activeLight = 0;
/** The light whose marker is being dragged, or null. */
let dragging = null;
let present = null;
let quiz = null;
/** Counts changes of the state: answers computed for an older one are dropped. */
let generation = 0;
/** The scale the error maps were last asked for (the three share one). */
let errorScale = 10;
/** The colour bar of the error scale, from the flat panel's last error map. */
let errorBar = null;

// ---- messages ----

function showMessage(text, kind = 'error') {
  const box = $('#message');
  box.classList.toggle('info', kind === 'info');
  box.querySelector('.message-text').textContent = text;
  box.hidden = false;
}

function clearMessage() {
  $('#message').hidden = true;
}

function summaryText(summary) {
  return t('model.summary', {
    name: summary.name,
    vertices: plural('count.vertices', summary.vertices),
    polygons: plural('count.polygons', summary.polygons),
    triangles: plural('count.triangles', summary.triangles),
  });
}

function setStatus(text) {
  // From here on the status says what happens now, not what the page said while loading.
  $('#status').removeAttribute('data-i18n');
  $('#status').textContent = text;
}

// ---- rendering ----

const modelInfo = () => models.find((m) => m.name === state.model) ?? null;
const errorsShown = () => state.errors && hasExactSurface(state) && !quiz?.on;
/** The state the panels draw: presenting draws them at the screen's pixels. */
const shownState = () => {
  const size = present?.renderSize();
  return size ? { ...state, size } : state;
};

/**
 * Whether one request draws the three panels (see panels.js): the three
 * methods of one scene and nothing else, and not while the Cost tab, which
 * compares the methods' times, is open (drawn together, they have one time).
 * Only with fewer than three cores: with three, the three workers draw at
 * the same time, and the slowest method alone takes less than the three
 * together in one worker (dragon, 480²: 8.4 ms against 13.5 in WebAssembly).
 */
const FEW_CORES = (navigator.hardwareConcurrency ?? 1) < 3;
/**
 * Drawn together on two cores, the first two panels' workers each draw half
 * of the three frames' rows at the same time (dragon, 480², in Chromium:
 * see BENCHMARKS.md, "Two workers, half the rows each").
 */
const GROUP_PARTS = (navigator.hardwareConcurrency ?? 1) >= 2 ? 2 : 1;
/** `auto` (by the cores), or `true`/`false` as a test sets it. */
let together = 'auto';
const drawnTogether = (errors) =>
  (together === 'auto' ? FEW_CORES : together) && !quiz?.on && !errors && view.tab !== 'cost' && panels.every((p) => state.overlays[p.method].length === 0);

/**
 * How many times the page's first view is drawn again, nothing changed,
 * right after its first frames. A fresh engine's first frames run while
 * the browser is still compiling its WebAssembly (each function on its
 * first call, then again, optimised, once it has run a while): in headless
 * Chromium on a 2-core machine the teapot's first frame took 130–220 ms,
 * the next two 6–13 and 2–5 ms, the later ones about 2. Drawn again while
 * no one is waiting, those frames warm the code before the first input,
 * and each restarts the captions' times (`settling` in panels.js), which
 * then show a warm frame's time instead of the first's. Any change of the
 * state ends them (`changed`).
 */
const SETTLING_FRAMES = 3;
/** How many of those frames are still to be asked for. */
let settling = SETTLING_FRAMES;
/** The panels whose frame of the first view drawn again has not come yet. */
let settleWaiting = new Set();

let linkTimer = 0;
/** Asks for the panels' frames of the state; `settle`: one of the first view's frames drawn again. */
function render(settle = false) {
  const errors = errorsShown();
  if (state.errorScale !== null) errorScale = state.errorScale;
  const shown = shownState();
  if (drawnTogether(errors)) {
    group.render({ scene: sceneToml(shown, panels[0].method), generation, gouraudSpecular: state.gouraudSpecular, settling: settle });
  } else for (const panel of panels) {
    panel.render({
      scene: quiz?.on ? quiz.sceneFor(panel.method) : sceneToml(shown, panel.method),
      overlays: quiz?.on ? '' : state.overlays[panel.method].join(','),
      errors: errors ? { scale: errorScale, exact: panel.method === 'flat', bar: panel.method === 'flat' ? [16, 200] : undefined } : null,
      generation,
      gouraudSpecular: state.gouraudSpecular,
      settling: settle,
    });
  }
  document.body.classList.toggle('showing-errors', errors);
  exactPanel.figure.hidden = !errors;
  if (errors !== exactShown) {
    exactShown = errors;
    if (present?.on) present.layout();
  }
  markPanels();
  clearTimeout(linkTimer);
  linkTimer = setTimeout(writeLink, 150);
}

/** Redraws the panels as the state says (after a measurement drew plain frames). */
function rerender() {
  render();
}

let exactShown = false;

function markPanels() {
  // The instruments' marks are in the pixels of the state's size: not while presenting.
  const plain = !present?.on && !quiz?.on;
  const profile = plain ? state.profile : null;
  for (const p of [...panels, exactPanel]) p.marks.set({ pixel: plain ? state.pixel : null, profile });
  markLights();
}

/** The lights' markers on every panel, from the camera of the panel's last frame. */
function markLights() {
  for (const p of panels) {
    const f = p.last;
    const markers = quiz?.on || !f ? [] : markerPositions(state.lights, f.view, f.width, f.height);
    for (const m of markers) {
      m.color = lightSwatch(state.lights[m.k]);
      m.active = m.k === activeLight;
    }
    p.marks.set({ lights: markers, circle: dragging !== null ? RADIUS : false });
  }
}

/** Lets the pointer find and move the lights' markers (interaction.js). */
const lightHandles = {
  active: () => activeLight,
  select: (k) => {
    activeLight = k;
    dragging = k;
    markLights();
  },
  at: (canvas, x, y, reach) => {
    const p = panels.find((q) => q.canvas === canvas);
    if (!p?.last || quiz?.on) return null;
    let best = null;
    for (const m of markerPositions(state.lights, p.last.view, p.last.width, p.last.height)) {
      const d = Math.hypot(m.x - x, m.y - y);
      if (d <= reach && (best === null || d < best.d)) best = { k: m.k, d };
    }
    return best?.k ?? null;
  },
  drag: (k, canvas, x, y) => {
    const p = panels.find((q) => q.canvas === canvas);
    if (!p?.last || !state.lights[k]) return;
    state.lights[k] = dragLight(state.lights[k], p.last.view, p.last.width, p.last.height, x, y);
  },
  release: () => {
    dragging = null;
    markLights();
  },
};

function writeLink() {
  const hash = toHash(state, view);
  if (hash !== location.hash && !(hash === '' && location.hash === '')) {
    history.replaceState(null, '', hash || location.pathname + location.search);
  }
}

function changed() {
  generation += 1;
  settling = 0;
  if (state.pixel && state.pixel.some((v) => v >= state.size)) state.pixel = null;
  if (state.profile?.row !== undefined && state.profile.row >= state.size) state.profile = { row: state.size - 1 };
  if (activeLight >= state.lights.length) activeLight = Math.max(0, state.lights.length - 1);
  // The workers start drawing at once; the controls catch up before the
  // paint that shows the new frames (dom.js: beforeNextPaint).
  render();
  beforeNextPaint(refreshControls);
}

function refreshControls() {
  form.refresh();
  side.refresh();
  present.refresh();
  side.tools.inspector.invalidate();
}

let lastError = '';
function panelError(panel, error) {
  const text = error.crashed
    ? t('error.crashed', { method: t(`panel.${panel.method}`), message: error.message })
    : t('error.render', { message: error.message });
  // The three panels usually fail together, for the same reason: say it once.
  if (text !== lastError || $('#message').hidden) showMessage(text);
  lastError = text;
}

function panelFrame(panel, frame) {
  // A good frame after a failed one: the render error has served its purpose
  // (any other message stays until dismissed).
  if (lastError && !$('#message').hidden && $('#message .message-text').textContent === lastError) clearMessage();
  lastError = '';
  if (frame.errors && panel.method === 'flat') {
    if (frame.exact) exactPanel.show(frame.exact);
    if (frame.bar) errorBar = frame.bar;
  }
  beforeNextPaint(markLights);
  if (settling > 0 && frame.generation === generation) settleAgain(panel, frame);
  if (panels.every((p) => p.last?.generation === frame.generation)) framesComplete();
}

/**
 * Draws the first view again (SETTLING_FRAMES) once each panel shows it,
 * then again once each has shown that frame. Asked for from the frame's
 * own report, before its panel is idle, so that the panels are never idle
 * between these frames (the tests' `idle` waits for them all).
 */
function settleAgain(panel, frame) {
  if (frame.settling) {
    settleWaiting.delete(panel);
    if (settleWaiting.size > 0) return;
  } else if (settling < SETTLING_FRAMES || !panels.every((p) => p.last?.generation === frame.generation)) {
    return;
  }
  settling -= 1;
  settleWaiting = new Set(panels);
  render(true);
}

/** All three panels show the same state: share the error scale, then let the instruments catch up. */
async function framesComplete() {
  if (panels.every((p) => p.last?.errors)) {
    const largest = Math.max(...panels.map((p) => p.last.errors.max));
    const scale = state.errorScale ?? heatScale(largest);
    errorScale = scale;
    await Promise.all(panels.map((p) => p.recolour(scale)));
  }
  side.tools.errors.update();
  scheduleInstruments();
}

let instrumentTimer = 0;
/** Whether an instrument update is waiting or running (for `instrumentsIdle`). */
let instrumentsBusy = false;
/** Runs the open instrument once the panels have been still for a moment. */
function scheduleInstruments() {
  clearTimeout(instrumentTimer);
  instrumentsBusy = true;
  instrumentTimer = setTimeout(runInstruments, 80);
}

async function runInstruments() {
  const mine = instrumentTimer;
  try {
    await Promise.all(panels.map((p) => p.idle()));
    // The instruments are out of sight while presenting and in the quiz.
    if (!present.on && !quiz.on) await side.update();
  } finally {
    if (mine === instrumentTimer) instrumentsBusy = false;
  }
}

// ---- the instruments, as the side panel and the panels ask for them ----

function setTab(name) {
  if (view.tab === name) return;
  const wasTogether = drawnTogether(errorsShown());
  view.tab = name;
  side.show();
  writeLink();
  // The Cost tab times each method: draw the panels apart (and together again after).
  if (drawnTogether(errorsShown()) !== wasTogether) render();
  else scheduleInstruments();
}

function inspectPixel(x, y) {
  state.pixel = [x, y];
  view.tab = 'inspector';
  side.show();
  changed();
}

const picks = {
  pixel: (x, y, canvas) => {
    const panel = panels.find((p) => p.canvas === canvas);
    if (quiz.on) {
      if (panel) quiz.clickPanel(panel.method, x, y);
      return;
    }
    inspectPixel(x, y);
  },
  row: (y) => {
    state.profile = { row: y };
    view.tab = 'profile';
    side.show();
    changed();
  },
  line: (line) => {
    state.profile = { line };
    view.tab = 'profile';
    side.show();
    changed();
  },
  hover: (at) => {
    if (view.tab === 'inspector' && !present.on && !quiz.on) side.tools.inspector.hover(at);
  },
  preview: (line) => {
    for (const p of [...panels, exactPanel]) p.marks.set({ preview: line });
  },
};

// ---- the user's file ----

async function openFile(file) {
  if (file.size > MAX_FILE_MIB * 1024 * 1024) {
    showMessage(t('error.kept', {
      message: t('error.tooLarge', { name: file.name, size: (file.size / 1048576).toFixed(1), limit: MAX_FILE_MIB }),
    }));
    return;
  }
  setStatus(t('model.loading', { name: file.name }));
  let bytes;
  try {
    bytes = await file.arrayBuffer();
  } catch (error) {
    showMessage(t('error.kept', { message: t('error.read', { name: file.name, message: error.message }) }));
    return;
  }
  // One panel parses the file; the others take the mesh it became.
  let summary;
  try {
    const parsed = await panels[0].loadFile(file.name, bytes);
    summary = parsed.summary;
    await Promise.all(panels.slice(1).map((p) => p.adoptFile(file.name, parsed.mesh)));
  } catch (error) {
    setStatus('');
    showMessage(t('error.kept', { message: t('error.file', { message: error.message }) }));
    return;
  }
  userFile = summary;
  clearMessage();
  setModel(userFile.name);
}

/**
 * Shows model `name` (built in, or the file loaded), framed: the camera
 * goes back to its start, which fits the model's bounding sphere.
 */
function setModel(name, notify = true) {
  const file = userFile && name === userFile.name ? userFile : null;
  state.model = name;
  state.detail = null;
  state.crease = null;
  state.camera = { ...defaultState().camera };
  if (state.normals === 'file' && !file?.has_normals) state.normals = 'auto';
  setStatus(file ? summaryText(file) : '');
  if (notify) changed();
}

// ---- languages ----

/** Loads the instruments' texts of `lang` from a panel's engine. */
async function labTexts(lang) {
  const reply = await panels[0].ask({ type: 'texts', lang });
  return reply.texts;
}

/** Shows the page in `lang`: every string, every control, every instrument. */
async function useLanguage(lang) {
  await setLanguage(lang, labTexts);
  translateDocument();
  $('#language').value = lang;
  for (const p of panels) {
    p.canvas.setAttribute('aria-label', t('panel.canvas', { method: t(`panel.${p.method}`) }));
    p.relabel();
  }
  exactPanel.canvas.setAttribute('aria-label', lab('method.exact'));
  if (form) {
    form = buildForm($('#controls'), page);
    side.build();
    if (present.on) present.build();
    quiz.draw();
    scheduleInstruments();
  }
}

function buildLanguageSwitch() {
  const select = $('#language');
  select.replaceChildren(...LANGUAGES.map((code) => {
    const option = document.createElement('option');
    option.value = code;
    option.lang = code;
    option.textContent = LANGUAGE_NAMES[code];
    return option;
  }));
  select.addEventListener('change', async () => {
    view.lang = select.value;
    await useLanguage(view.lang);
    writeLink();
  });
}

// ---- what the form and the instruments see of the page ----

const page = {
  state: () => state,
  get view() { return view; },
  get panels() { return panels; },
  get exactPanel() { return exactPanel; },
  get generation() { return generation; },
  get errorBar() { return errorBar; },
  models: () => models,
  modelName: (name) => t(`model.name.${name}`),
  modelInfo,
  setModel,
  setActiveLight: (k) => {
    if (activeLight === k) return;
    activeLight = k;
    markLights();
  },
  visiblePanels: () => (errorsShown() ? [exactPanel, ...panels] : panels),
  size: () => shownState().size,
  ask: (method, request) => panels.find((p) => p.method === method).ask(request),
  userFile: () => userFile,
  dragMode: () => dragMode,
  setDragMode: (v) => (dragMode = v),
  changed: () => changed(),
  rerender,
  openFile,
  resetCamera,
  setStatus,
  showMessage,
  summaryText,
  sceneFor: (method) => sceneToml(state, method),
  setTab,
  inspectPixel,
  errorsShown,
};

/** Saves one orbit of the panels as an animated PNG (export.js). */
const saveAnimation = () => saveOrbit(page, $('#export-animation'));

function resetCamera() {
  state.camera = { ...defaultState().camera };
  changed();
}

// ---- start ----

function applyLink() {
  const { state: linked, view: linkedView, invalid } = fromHash(location.hash);
  const messages = invalid.map((key) => t('error.linkValue', { key }));
  const isBuiltin = models.some((m) => m.name === linked.model);
  if (!isBuiltin && !(userFile && linked.model === userFile.name)) {
    messages.unshift(t('error.linkFile', { name: linked.model }));
    linked.model = defaultState().model;
    linked.detail = null;
    linked.crease = null;
  }
  state = linked;
  view = linkedView;
  return messages;
}

async function start() {
  translateDocument();
  if (typeof Worker === 'undefined' || typeof WebAssembly === 'undefined') {
    showMessage(t('error.noWorkers'));
    return;
  }
  let module;
  try {
    module = await WebAssembly.compileStreaming(fetch('shadelab.wasm'));
  } catch (error) {
    showMessage(t('error.noWasm', { message: error.message }));
    return;
  }
  const figures = [...document.querySelectorAll('.panel')];
  panels = METHODS.map((method) => {
    const figure = figures.find((f) => f.dataset.method === method);
    const panel = new Panel(method, figure, module);
    panel.onerror = panelError;
    panel.onframe = panelFrame;
    return panel;
  });
  group = new PanelGroup(panels, GROUP_PARTS);
  group.onerror = panelError;
  exactPanel = new ImagePanel('exact', figures.find((f) => f.dataset.method === 'exact'));
  holdPaintWorkWhile(() => panels.some((p) => p.busy));
  try {
    const answers = await Promise.all(panels.map((p) => p.ready));
    models = answers[0].models;
  } catch (error) {
    showMessage(t('error.noWasm', { message: error.message }));
    return;
  }
  const messages = applyLink();
  buildLanguageSwitch();
  await useLanguage(view.lang ?? negotiate(navigator.languages ?? [navigator.language]));
  // The link's complaints, in the page's language.
  if (messages.length) showMessage(applyLink().join('\n'), 'info');
  setStatus('');
  present = new Present(page);
  quiz = new Quiz(page);
  form = buildForm($('#controls'), page);
  side = new Side($('#side'), page);
  side.build();
  attachInteraction([...panels, exactPanel].map((p) => p.canvas), state, changed, () => dragMode, resetCamera, picks, lightHandles);
  attachDrop($('#panels'), openFile);
  $('#message .message-close').addEventListener('click', clearMessage);
  $('#controls').addEventListener('submit', (e) => e.preventDefault());
  $('#export-png').addEventListener('click', () => exportPng(panels));
  $('#export-animation').addEventListener('click', saveAnimation);
  $('#export-scene').addEventListener('click', () => exportScene(state, userFile));
  $('#copy-link').addEventListener('click', async () => {
    writeLink();
    try {
      await navigator.clipboard.writeText(location.href);
      showMessage(t('view.link.copied'), 'info');
    } catch (_) {
      showMessage(t('view.link.shown'), 'info');
    }
  });
  $('#reset-all').addEventListener('click', () => {
    const model = state.model;
    state = Object.assign(state, defaultState());
    if (userFile && model === userFile.name) state.model = model;
    clearMessage();
    changed();
  });
  $('#present').addEventListener('click', () => present.toggle());
  $('#quiz').addEventListener('click', () => quiz.toggle());
  // Enlarged panels show their pixels as squares; reduced, smoothed.
  const scaled = new ResizeObserver((entries) => {
    for (const e of entries) e.target.classList.toggle('enlarged', e.target.clientWidth * (window.devicePixelRatio || 1) >= e.target.width);
  });
  for (const p of [...panels, exactPanel]) scaled.observe(p.canvas);
  window.addEventListener('hashchange', async () => {
    if (location.hash === toHash(state, view)) return;
    const keep = state;
    const keepLang = view.lang;
    const problems = applyLink();
    if (problems.length) showMessage(problems.join('\n'), 'info');
    // The controls and the pointer handlers hold the state object: update it in place.
    state = Object.assign(keep, state);
    if (view.lang !== keepLang) await useLanguage(view.lang ?? negotiate(navigator.languages ?? []));
    side.show();
    changed();
  });
  // `state` is replaced by applyLink only before the controls exist; from
  // here on it is the same object, changed in place.
  if (globalThis.SHADELAB_TEST_HOOKS === true) {
    exposeForTests(page, {
      instrumentsBusy: () => instrumentsBusy,
      side: () => side,
      drawTogether(mode, parts = group.parts) {
        together = mode;
        group.parts = parts;
        render();
      },
      panelScene: (method) => (quiz.on ? quiz.sceneFor(method) : sceneToml(shownState(), method)),
      present: () => present,
      quiz: () => quiz,
      saveAnimation,
    });
  }
  render();
}

start();
