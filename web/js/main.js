// The viewer: three panels (flat | Gouraud | Phong), each rendered by
// shadelab's WebAssembly in its own worker from the same scene file, and the
// controls that change that scene. Everything the page knows is in `state`;
// every change re-renders the three panels and rewrites the link.
import { t, translateDocument, formatCount } from './i18n.js';
import { Panel } from './panels.js';
import { Controls } from './controls.js';
import { attachInteraction } from './interaction.js';
import { exportPng, exportScene } from './export.js';
import {
  METHODS, PANEL_SIZES, PRESETS, MAX_FILE_MIB, MESH_EXTENSIONS, DEFAULT_LIGHT_POSITION, ZOOM_MIN, ZOOM_MAX,
  defaultState, sceneToml, toHash, fromHash, presetOf,
} from './state.js';

const $ = (selector) => document.querySelector(selector);

let state = defaultState();
let models = [];
/** The user's file as loaded into the engines: its summary, or null. */
let userFile = null;
let panels = [];
let controls = null;
let dragMode = 'camera';

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
    vertices: formatCount(summary.vertices),
    polygons: formatCount(summary.polygons),
    triangles: formatCount(summary.triangles),
  });
}

function setStatus(text) {
  $('#status').textContent = text;
}

// ---- rendering ----

const modelInfo = () => models.find((m) => m.name === state.model) ?? null;

let linkTimer = 0;
function render() {
  for (const panel of panels) panel.render(sceneToml(state, panel.method));
  clearTimeout(linkTimer);
  linkTimer = setTimeout(writeLink, 150);
}

function writeLink() {
  const hash = toHash(state);
  if (hash !== location.hash && !(hash === '' && location.hash === '')) {
    history.replaceState(null, '', hash || location.pathname + location.search);
  }
}

function changed() {
  if (state.polygons === 'whole') state.rasterizer = 'scanline';
  controls.refresh();
  render();
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

function panelFrame() {
  // A good frame after a failed one: the render error has served its purpose
  // (any other message stays until dismissed).
  if (lastError && !$('#message').hidden && $('#message .message-text').textContent === lastError) clearMessage();
  lastError = '';
}

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
  let summaries;
  try {
    summaries = await Promise.all(panels.map((p) => p.loadFile(file.name, bytes)));
  } catch (error) {
    setStatus('');
    showMessage(t('error.kept', { message: error.message }));
    return;
  }
  userFile = summaries[0];
  clearMessage();
  state.model = userFile.name;
  state.detail = null;
  state.crease = null;
  if (state.normals === 'file' && !userFile.has_normals) state.normals = 'auto';
  setStatus(summaryText(userFile));
  changed();
}

function attachDrop(zone) {
  let depth = 0;
  zone.addEventListener('dragenter', (e) => {
    if (![...e.dataTransfer.types].includes('Files')) return;
    depth += 1;
    zone.classList.add('dragging');
    e.preventDefault();
  });
  zone.addEventListener('dragover', (e) => {
    if ([...e.dataTransfer.types].includes('Files')) e.preventDefault();
  });
  zone.addEventListener('dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (depth === 0) zone.classList.remove('dragging');
  });
  zone.addEventListener('drop', (e) => {
    e.preventDefault();
    depth = 0;
    zone.classList.remove('dragging');
    const file = e.dataTransfer.files[0];
    if (file) openFile(file);
  });
}

// ---- controls ----

function resetCamera() {
  state.camera = { ...defaultState().camera };
  changed();
}

function buildControls() {
  const c = new Controls($('#controls'), changed);
  const options = (prefix, values) => values.map((v) => [v, t(`${prefix}.${v}`)]);

  const model = c.group('group.model', 'model');
  c.select(model, {
    name: 'model',
    label: t('model.source'),
    options: () => [
      ...models.map((m) => [m.name, m.name]),
      ...(userFile ? [[userFile.name, userFile.name]] : []),
    ],
    get: () => state.model,
    set: (v) => {
      state.model = v;
      state.detail = null;
      state.crease = null;
      if (state.normals === 'file' && !(userFile && v === userFile.name && userFile.has_normals)) state.normals = 'auto';
      setStatus(userFile && v === userFile.name ? summaryText(userFile) : '');
    },
  });
  c.range(model, {
    name: 'detail',
    label: t('model.detail'),
    min: () => modelInfo()?.detail_min ?? 0,
    max: () => modelInfo()?.detail_max ?? 1,
    step: 1,
    get: () => state.detail ?? modelInfo()?.default_detail ?? 0,
    set: (v) => (state.detail = Math.round(v)),
    hint: () => (modelInfo() ? t('model.detail.hint', { meaning: modelInfo().detail_meaning }) : ''),
    visible: () => modelInfo() !== null,
  });
  c.note(model, () => modelInfo()?.description ?? '');
  c.file(model, {
    name: 'file',
    label: t('model.file'),
    accept: MESH_EXTENSIONS.map((e) => `.${e}`).join(','),
    hint: t('model.file.hint', { limit: MAX_FILE_MIB }),
    onfile: openFile,
  });

  const ambient = c.group('group.ambient', 'ambient');
  c.rgb(ambient, { name: 'ambient-color', label: t('ambient.color'), get: () => state.ambient.color, set: (v) => (state.ambient.color = v) });
  c.range(ambient, { name: 'ambient-intensity', label: t('ambient.intensity'), min: 0, max: 2, step: 0.01, get: () => state.ambient.intensity, set: (v) => (state.ambient.intensity = v) });

  const light = c.group('group.light', 'light');
  c.rgb(light, { name: 'light-color', label: t('light.color'), get: () => state.light.color, set: (v) => (state.light.color = v) });
  c.range(light, { name: 'light-intensity', label: t('light.intensity'), min: 0, max: 3, step: 0.01, get: () => state.light.intensity, set: (v) => (state.light.intensity = v) });
  for (const [axis, i] of [['x', 0], ['y', 1], ['z', 2]]) {
    c.range(light, {
      name: `light-${axis}`, label: t(`light.${axis}`), min: -10, max: 10, step: 0.05,
      get: () => state.light.position[i],
      set: (v) => { const p = [...state.light.position]; p[i] = v; state.light.position = p; },
    });
  }
  c.button(light, { label: t('light.reset'), onclick: () => { state.light.position = [...DEFAULT_LIGHT_POSITION]; changed(); } });

  const material = c.group('group.material', 'material');
  c.select(material, {
    name: 'preset',
    label: t('material.preset'),
    options: () => [['custom', t('material.preset.custom'), true], ...Object.keys(PRESETS).map((p) => [p, t(`material.preset.${p}`)])],
    get: () => presetOf(state.material),
    set: (v) => { if (PRESETS[v]) state.material = structuredClone(PRESETS[v]); },
  });
  for (const k of ['ka', 'kd', 'ks']) {
    c.rgb(material, { name: k, label: t(`material.${k}`), get: () => state.material[k], set: (v) => (state.material[k] = v) });
  }
  c.range(material, { name: 'shininess', label: t('material.shininess'), min: 0, max: 256, step: 1, get: () => state.material.shininess, set: (v) => (state.material.shininess = v) });

  const camera = c.group('group.camera', 'camera');
  c.range(camera, { name: 'yaw', label: t('camera.yaw'), min: -180, max: 180, step: 1, get: () => ((((state.camera.yaw + 180) % 360) + 360) % 360) - 180, set: (v) => (state.camera.yaw = v) });
  c.range(camera, { name: 'pitch', label: t('camera.pitch'), min: -89, max: 89, step: 1, get: () => state.camera.pitch, set: (v) => (state.camera.pitch = v) });
  c.range(camera, { name: 'zoom', label: t('camera.zoom'), min: ZOOM_MIN, max: ZOOM_MAX, step: 0.01, get: () => state.camera.zoom, set: (v) => (state.camera.zoom = v) });
  c.select(camera, {
    name: 'drag', label: t('camera.drag'), options: () => options('camera.drag', ['camera', 'light']),
    get: () => dragMode, set: (v) => (dragMode = v),
  });
  c.button(camera, { label: t('camera.reset'), onclick: resetCamera });
  c.note(camera, () => t('camera.help'));

  const shading = c.group('group.shading', 'shading');
  c.select(shading, {
    name: 'normals', label: t('shading.normals'),
    options: () => options('shading.normals', ['auto', 'file', 'uniform', 'area', 'angle']).map(([v, l]) => [v, l, v === 'file' && !(userFile && state.model === userFile.name && userFile.has_normals)]),
    get: () => state.normals, set: (v) => (state.normals = v),
  });
  c.range(shading, {
    name: 'crease', label: t('shading.crease'), min: 0, max: 180, step: 1,
    get: () => state.crease ?? modelInfo()?.default_crease ?? 180, set: (v) => (state.crease = v),
    hint: () => t('shading.crease.hint'),
  });
  c.checkbox(shading, { name: 'gouraud-specular', label: t('shading.gouraudSpecular'), get: () => state.gouraudSpecular, set: (v) => (state.gouraudSpecular = v) });
  c.select(shading, { name: 'interpolation', label: t('shading.interpolation'), options: () => options('shading.interpolation', ['perspective', 'screen']), get: () => state.interpolation, set: (v) => (state.interpolation = v) });
  c.checkbox(shading, { name: 'cull', label: t('shading.cull'), get: () => state.cull, set: (v) => (state.cull = v) });
  c.select(shading, { name: 'specular', label: t('shading.specular'), options: () => options('shading.specular', ['phong', 'blinn-phong']), get: () => state.specular, set: (v) => (state.specular = v) });
  c.select(shading, { name: 'polygons', label: t('shading.polygons'), options: () => options('shading.polygons', ['fans', 'whole']), get: () => state.polygons, set: (v) => (state.polygons = v) });
  c.select(shading, {
    name: 'rasterizer', label: t('shading.rasterizer'),
    options: () => options('shading.rasterizer', ['tiled', 'scanline']).map(([v, l]) => [v, l, v === 'tiled' && state.polygons === 'whole']),
    get: () => state.rasterizer, set: (v) => (state.rasterizer = v),
  });

  const view = c.group('group.view', 'view');
  c.select(view, {
    name: 'size', label: t('view.size'),
    options: () => [...new Set([...PANEL_SIZES, state.size])].sort((a, b) => a - b).map((s) => [String(s), `${s} × ${s}`]),
    get: () => String(state.size), set: (v) => (state.size = Number(v)),
  });
  c.rgb(view, { name: 'background', label: t('view.background'), get: () => state.background, set: (v) => (state.background = v) });
  return c;
}

// ---- start ----

function applyLink() {
  const { state: linked, invalid } = fromHash(location.hash);
  const messages = invalid.map((key) => t('error.linkValue', { key }));
  const isBuiltin = models.some((m) => m.name === linked.model);
  if (!isBuiltin && !(userFile && linked.model === userFile.name)) {
    messages.unshift(t('error.linkFile', { name: linked.model }));
    linked.model = defaultState().model;
    linked.detail = null;
    linked.crease = null;
  }
  state = linked;
  if (messages.length) showMessage(messages.join('\n'), 'info');
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
    panel.canvas.setAttribute('aria-label', t('panel.canvas', { method: t(`panel.${method}`) }));
    panel.onerror = panelError;
    panel.onframe = panelFrame;
    return panel;
  });
  try {
    const answers = await Promise.all(panels.map((p) => p.ready));
    models = answers[0].models;
  } catch (error) {
    showMessage(t('error.noWasm', { message: error.message }));
    return;
  }
  setStatus('');
  applyLink();
  controls = buildControls();
  attachInteraction(panels.map((p) => p.canvas), state, changed, () => dragMode, resetCamera);
  attachDrop($('#panels'));
  $('#message .message-close').addEventListener('click', clearMessage);
  $('#controls').addEventListener('submit', (e) => e.preventDefault());
  $('#export-png').addEventListener('click', () => exportPng(panels));
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
  $('#present').addEventListener('click', (e) => {
    const on = document.body.classList.toggle('presenting');
    e.currentTarget.setAttribute('aria-pressed', String(on));
  });
  window.addEventListener('hashchange', () => {
    if (location.hash === toHash(state)) return;
    const keep = state;
    applyLink();
    // The controls and the pointer handlers hold the state object: update it in place.
    state = Object.assign(keep, state);
    changed();
  });
  // `state` is replaced by applyLink only before the controls exist; from
  // here on it is the same object, changed in place.
  exposeForTests();
  render();
}

/** A small handle for the browser tests and for the curious (devtools). */
function exposeForTests() {
  window.shadelab = {
    get state() { return state; },
    panels,
    sceneToml: (method) => sceneToml(state, method),
    update(patch) {
      patch(state);
      changed();
    },
    idle: () => Promise.all(panels.map((p) => p.idle())),
    frameTimes: () => Object.fromEntries(panels.map((p) => [p.method, [...p.times]])),
    openFile,
  };
}

start();
