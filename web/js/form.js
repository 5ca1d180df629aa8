// The control groups under the panels: every parameter of the scene the
// three panels render, declared group by group (controls.js builds them).
// Built again when the language changes.
import { t, lab } from './i18n.js';
import { Controls } from './controls.js';
import {
  PANEL_SIZES, PRESETS, MAX_FILE_MIB, MESH_EXTENSIONS, DEFAULT_LIGHT_POSITION, ZOOM_MIN, ZOOM_MAX,
  FIXED_POINT_BITS, PALETTE_SHADES, presetOf, needsScanline, rasterizerOf,
} from './state.js';

/**
 * Builds the controls into `form`. `page` gives: state(), models(),
 * modelInfo(), userFile(), dragMode get/set, changed(), openFile(file),
 * resetCamera(), setStatus(text), summaryText(summary).
 */
export function buildForm(form, page) {
  form.replaceChildren();
  const c = new Controls(form, page.changed);
  const s = page.state;
  const options = (prefix, values) => values.map((v) => [v, t(`${prefix}.${v}`)]);
  const modelName = (name) => (page.models().some((m) => m.name === name) ? t(`model.name.${name}`) : name);

  const model = c.group('group.model', 'model');
  c.select(model, {
    name: 'model',
    label: t('model.source'),
    options: () => [
      ...page.models().map((m) => [m.name, modelName(m.name)]),
      ...(page.userFile() ? [[page.userFile().name, page.userFile().name]] : []),
    ],
    get: () => s().model,
    set: (v) => {
      const st = s();
      const file = page.userFile();
      st.model = v;
      st.detail = null;
      st.crease = null;
      if (st.normals === 'file' && !(file && v === file.name && file.has_normals)) st.normals = 'auto';
      page.setStatus(file && v === file.name ? page.summaryText(file) : '');
    },
  });
  c.range(model, {
    name: 'detail',
    label: t('model.detail'),
    min: () => page.modelInfo()?.detail_min ?? 0,
    max: () => page.modelInfo()?.detail_max ?? 1,
    step: 1,
    get: () => s().detail ?? page.modelInfo()?.default_detail ?? 0,
    set: (v) => (s().detail = Math.round(v)),
    hint: () => (page.modelInfo() ? t(`model.detailMeaning.${page.modelInfo().name}`) : ''),
    visible: () => page.modelInfo() !== null,
  });
  c.note(model, () => (page.modelInfo() ? t(`model.about.${page.modelInfo().name}`) : ''));
  c.file(model, {
    name: 'file',
    label: t('model.file'),
    accept: MESH_EXTENSIONS.map((e) => `.${e}`).join(','),
    hint: t('model.file.hint', { limit: MAX_FILE_MIB }),
    onfile: page.openFile,
  });

  const ambient = c.group('group.ambient', 'ambient');
  c.rgb(ambient, { name: 'ambient-color', label: t('ambient.color'), get: () => s().ambient.color, set: (v) => (s().ambient.color = v) });
  c.range(ambient, { name: 'ambient-intensity', label: t('ambient.intensity'), min: 0, max: 2, step: 0.01, get: () => s().ambient.intensity, set: (v) => (s().ambient.intensity = v) });

  const light = c.group('group.light', 'light');
  c.rgb(light, { name: 'light-color', label: t('light.color'), get: () => s().light.color, set: (v) => (s().light.color = v) });
  c.range(light, { name: 'light-intensity', label: t('light.intensity'), min: 0, max: 3, step: 0.01, get: () => s().light.intensity, set: (v) => (s().light.intensity = v) });
  for (const [axis, i] of [['x', 0], ['y', 1], ['z', 2]]) {
    c.range(light, {
      name: `light-${axis}`, label: t(`light.${axis}`), min: -10, max: 10, step: 0.05,
      get: () => s().light.position[i],
      set: (v) => { const p = [...s().light.position]; p[i] = v; s().light.position = p; },
    });
  }
  c.button(light, { label: t('light.reset'), onclick: () => { s().light.position = [...DEFAULT_LIGHT_POSITION]; page.changed(); } });

  const material = c.group('group.material', 'material');
  c.select(material, {
    name: 'preset',
    label: t('material.preset'),
    options: () => [['custom', t('material.preset.custom'), true], ...Object.keys(PRESETS).map((p) => [p, t(`material.preset.${p}`)])],
    get: () => presetOf(s().material),
    set: (v) => { if (PRESETS[v]) s().material = structuredClone(PRESETS[v]); },
  });
  for (const k of ['ka', 'kd', 'ks']) {
    c.rgb(material, { name: k, label: t(`material.${k}`), get: () => s().material[k], set: (v) => (s().material[k] = v) });
  }
  c.range(material, { name: 'shininess', label: t('material.shininess'), min: 0, max: 256, step: 1, get: () => s().material.shininess, set: (v) => (s().material.shininess = v) });

  const camera = c.group('group.camera', 'camera');
  c.range(camera, { name: 'yaw', label: t('camera.yaw'), min: -180, max: 180, step: 1, get: () => ((((s().camera.yaw + 180) % 360) + 360) % 360) - 180, set: (v) => (s().camera.yaw = v) });
  c.range(camera, { name: 'pitch', label: t('camera.pitch'), min: -89, max: 89, step: 1, get: () => s().camera.pitch, set: (v) => (s().camera.pitch = v) });
  c.range(camera, { name: 'zoom', label: t('camera.zoom'), min: ZOOM_MIN, max: ZOOM_MAX, step: 0.01, get: () => s().camera.zoom, set: (v) => (s().camera.zoom = v) });
  c.select(camera, {
    name: 'drag', label: t('camera.drag'), options: () => options('camera.drag', ['camera', 'light']),
    get: () => page.dragMode(), set: (v) => page.setDragMode(v),
  });
  c.button(camera, { label: t('camera.reset'), onclick: page.resetCamera });
  c.note(camera, () => t('camera.help'));

  const shading = c.group('group.shading', 'shading');
  c.select(shading, {
    name: 'normals', label: t('shading.normals'),
    options: () => options('shading.normals', ['auto', 'file', 'uniform', 'area', 'angle']).map(([v, l]) => {
      const file = page.userFile();
      return [v, l, v === 'file' && !(file && s().model === file.name && file.has_normals)];
    }),
    get: () => s().normals, set: (v) => (s().normals = v),
  });
  c.range(shading, {
    name: 'crease', label: t('shading.crease'), min: 0, max: 180, step: 1,
    get: () => s().crease ?? page.modelInfo()?.default_crease ?? 180, set: (v) => (s().crease = v),
    hint: () => t('shading.crease.hint'),
  });
  c.checkbox(shading, { name: 'gouraud-specular', label: t('shading.gouraudSpecular'), get: () => s().gouraudSpecular, set: (v) => (s().gouraudSpecular = v) });
  c.select(shading, { name: 'interpolation', label: t('shading.interpolation'), options: () => options('shading.interpolation', ['perspective', 'screen']), get: () => s().interpolation, set: (v) => (s().interpolation = v) });
  c.details(shading, { summary: t('explain.summary'), text: () => lab(`about.interpolation_${s().interpolation}`) });
  c.checkbox(shading, { name: 'cull', label: t('shading.cull'), get: () => s().cull, set: (v) => (s().cull = v) });
  c.select(shading, { name: 'specular', label: t('shading.specular'), options: () => options('shading.specular', ['phong', 'blinn-phong']), get: () => s().specular, set: (v) => (s().specular = v) });
  c.note(shading, () => t(`shading.specular.${s().specular}.hint`));
  c.details(shading, { summary: t('shading.specular.explain'), text: () => lab('about.blinn') });

  // Interpolation on polygons, and the modes of old hardware: all drawn by the scanline rasterizer.
  const polygons = c.group('group.polygons', 'polygons');
  c.select(polygons, { name: 'polygons', label: t('shading.polygons'), options: () => options('shading.polygons', ['fans', 'whole']), get: () => s().polygons, set: (v) => (s().polygons = v) });
  c.details(polygons, { summary: t('explain.summary'), text: () => lab(`about.polygons_${s().polygons}`) });
  c.checkbox(polygons, {
    name: 'fixed-point', label: t('polygons.fixedPoint'),
    get: () => s().fixedPoint !== null, set: (v) => (s().fixedPoint = v ? 8 : null),
  });
  c.range(polygons, {
    name: 'fixed-bits', label: t('polygons.fixedBits'), min: FIXED_POINT_BITS[0], max: FIXED_POINT_BITS[1], step: 1,
    get: () => s().fixedPoint ?? 8, set: (v) => (s().fixedPoint = Math.round(v)),
    visible: () => s().fixedPoint !== null,
  });
  c.details(polygons, { summary: t('polygons.fixedPoint.explain'), text: () => lab('about.fixed_point') });
  c.checkbox(polygons, {
    name: 'palette', label: t('polygons.palette'),
    get: () => s().palette !== null, set: (v) => (s().palette = v ? { shades: 8, offset: 0 } : null),
  });
  c.range(polygons, {
    name: 'palette-shades', label: t('polygons.shades'), min: PALETTE_SHADES[0], max: PALETTE_SHADES[1], step: 1,
    get: () => s().palette?.shades ?? 8,
    set: (v) => {
      const shades = Math.round(v);
      s().palette = { shades, offset: Math.min(s().palette?.offset ?? 0, 256 - shades) };
    },
    visible: () => s().palette !== null,
  });
  c.range(polygons, {
    name: 'palette-offset', label: t('polygons.offset'), min: 0, max: () => 256 - (s().palette?.shades ?? 8), step: 1,
    get: () => s().palette?.offset ?? 0,
    set: (v) => (s().palette = { shades: s().palette?.shades ?? 8, offset: Math.round(v) }),
    hint: () => t('polygons.offset.hint'),
    visible: () => s().palette !== null,
  });
  c.details(polygons, { summary: t('polygons.palette.explain'), text: () => lab('about.palette') });
  c.select(polygons, {
    name: 'rasterizer', label: t('shading.rasterizer'),
    options: () => options('shading.rasterizer', ['tiled', 'scanline']).map(([v, l]) => [v, l, v === 'tiled' && needsScanline(s())]),
    get: () => rasterizerOf(s()), set: (v) => (s().rasterizer = v),
  });
  c.note(polygons, () => (needsScanline(s()) ? t('polygons.scanlineOnly') : t('polygons.rasterizer.hint')));

  const view = c.group('group.view', 'view');
  c.select(view, {
    name: 'size', label: t('view.size'),
    options: () => [...new Set([...PANEL_SIZES, s().size])].sort((a, b) => a - b).map((n) => [String(n), `${n} × ${n}`]),
    get: () => String(s().size), set: (v) => (s().size = Number(v)),
  });
  c.rgb(view, { name: 'background', label: t('view.background'), get: () => s().background, set: (v) => (s().background = v) });
  return c;
}
