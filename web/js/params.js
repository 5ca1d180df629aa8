// Every parameter the page's controls set: its name (the path in the
// page's state), the key that carries it in a link, the group of controls
// it belongs to, and how its control shows it (the span its slider covers,
// its step, the digits a link keeps). A parameter of the scene names its
// scene-file `key`: its kind, default, valid range, unit, help, English
// label, the names of its three parts and its choices come from the core's
// table of parameters, which the server hands out as `params.json` and this
// module reads before any other module of the page runs
// (shadelab_core::params). The state's defaults, the link's reading and
// writing and the scene file (state.js) and the controls with their labels
// (form.js) are derived from this: a new ordinary parameter is one line
// here.
//
// Kinds: 'number' (float), 'int', 'choice' (one of `choices`), 'bool',
// 'rgb' (three integers within `min`..`max`), 'vec3' (three numbers, each
// within `min`..`max`, named by `parts`). `min`/`max` are the values
// accepted (from a number box or a link); `slider` is the span of the
// slider when it is narrower. `nullable`: null is a value (the model's own,
// or the mode off); `on` is the value a mode starts from when it is
// switched on. `control`: the name of its control when it is not the
// parameter's name within its group (form.js: controlName). A parameter of
// group 'light' belongs to each light of the `lights` list; `when(light)`
// says which lights have it (a point light's position, a directional
// light's direction). The page's own parameters (the panel size, the
// instruments, the animation), which no scene file has, are declared here
// whole.

/** The core's schema: {params: [{key, kind, default, typical, min, max, unit, help, label, parts}], choices: [{key, what, default, values}]}. */
const SCHEMA = await fetch(new URL('../params.json', import.meta.url)).then((response) => {
  if (!response.ok) throw new Error(`params.json: ${response.status} ${response.statusText}`);
  return response.json();
});

/** The shading methods, in the order the page shows their panels: the core's `render.shading` choice. */
export const METHODS = (() => {
  const shading = SCHEMA.choices.find((c) => c.key === 'render.shading');
  if (!shading) throw new Error('params.json has no choice render.shading');
  return shading.values.map((v) => v.name);
})();

/** The groups of controls, in the order the page shows them. */
export const GROUPS = ['model', 'ambient', 'lights', 'material', 'camera', 'shading', 'polygons', 'view'];

/** The lights a scene may have in the viewer. */
export const MAX_LIGHTS = 8;

const KINDS = { number: 'number', integer: 'int', rgb: 'rgb', vec3: 'vec3', bool: 'bool' };

/**
 * `p` completed from the schema's entry for its scene-file key. `order` is
 * the entry's place in the core's table, the order the scene file and a
 * light's link fields follow; `label` is its English label (a choice's:
 * what it chooses).
 */
function fromSchema(p) {
  const c = SCHEMA.choices.findIndex((q) => q.key === (p.choicesOf ?? p.key));
  if (p.choicesOf && c < 0) throw new Error(`params.json has no choice ${p.choicesOf}`);
  if (c >= 0) {
    const choice = SCHEMA.choices[c];
    const values = { kind: 'choice', choices: choice.values.map((v) => v.name), default: choice.default };
    // A choice the page writes itself (a light's kind, the normals): only its values and default.
    if (p.choicesOf) return { ...p, ...values };
    const label = choice.what.charAt(0).toUpperCase() + choice.what.slice(1);
    return { ...p, ...values, label, parts: [], order: SCHEMA.params.length + c };
  }
  if (!p.key) return p;
  const i = SCHEMA.params.findIndex((q) => q.key === p.key);
  if (i < 0) throw new Error(`params.json has no ${p.key}`);
  const s = SCHEMA.params[i];
  const typical = s.typical ?? undefined;
  return {
    ...p,
    kind: KINDS[s.kind] ?? p.kind,
    default: p.nullable ? s.default : (s.default ?? typical),
    on: typical,
    min: s.min,
    max: s.max,
    unit: s.unit,
    help: s.help,
    label: s.label,
    parts: s.parts,
    order: i,
  };
}

/** A point light's parameters, and a directional light's. */
const point = (light) => light.kind === 'point';
const directional = (light) => light.kind === 'directional';

export const PARAMS = [
  // The model: its name, its tessellation (each model has its own range within the one given).
  { name: 'model', key: 'model.source', link: 'model', group: 'model', kind: 'model' },
  { name: 'detail', key: 'model.detail', link: 'detail', group: 'model', nullable: true, step: 1 },

  { name: 'ambient.color', key: 'ambient.color', link: 'ambient', group: 'ambient', control: 'ambient-color' },
  { name: 'ambient.intensity', key: 'ambient.intensity', link: 'ambientI', group: 'ambient', control: 'ambient-intensity', slider: [0, 2], step: 0.01 },

  // Each light of the list (group 'light'); the list itself is `lights`.
  // `inEveryLink`: a field every `lights=` link has (those it had before
  // attenuation); the others follow in the order declared here, left out
  // at their defaults: a new light parameter goes last (state.js:
  // LIGHT_FIELDS). A vector's sliders are named by its parts alone
  // (light-1-x).
  { name: 'on', link: 'on', group: 'light', kind: 'bool', default: true },
  { name: 'kind', choicesOf: 'lights.kind', link: 'kind', group: 'light' },
  { name: 'color', key: 'lights.color', link: 'light', group: 'light', inEveryLink: true },
  { name: 'intensity', key: 'lights.intensity', link: 'lightI', group: 'light', inEveryLink: true, slider: [0, 3], step: 0.01 },
  { name: 'position', key: 'lights.position', link: 'lightPos', group: 'light', when: point, inEveryLink: true, control: '', slider: [-10, 10], step: 0.05 },
  // A direction of zero has no meaning (`nonzero`).
  { name: 'direction', key: 'lights.direction', link: 'lightDir', group: 'light', when: directional, inEveryLink: true, control: '', nonzero: true, slider: [-1, 1], step: 0.01 },
  // A point light's fall-off with distance: k0 + k1·d + k2·d² divides its light.
  { name: 'attenuation', key: 'lights.attenuation', link: 'lightAtt', group: 'light', when: point, slider: [0, 1], step: 0.01 },

  { name: 'material.ka', key: 'material.ka', link: 'ka', group: 'material' },
  { name: 'material.kd', key: 'material.kd', link: 'kd', group: 'material' },
  { name: 'material.ks', key: 'material.ks', link: 'ks', group: 'material' },
  { name: 'material.shininess', key: 'material.shininess', link: 'shininess', group: 'material', slider: [0, 256], step: 1 },

  { name: 'camera.yaw', key: 'render.yaw', link: 'yaw', group: 'camera', slider: [-180, 180], step: 1, wrap: 360, digits: 2 },
  { name: 'camera.pitch', key: 'render.pitch', link: 'pitch', group: 'camera', slider: [-89, 89], step: 1, digits: 2 },
  { name: 'camera.zoom', key: 'render.zoom', link: 'zoom', group: 'camera', slider: [0.25, 8], step: 0.01 },

  { name: 'normals', choicesOf: 'model.normals', link: 'normals', group: 'shading' },
  { name: 'crease', key: 'model.crease_angle', link: 'crease', group: 'shading', nullable: true, step: 1 },
  { name: 'gouraudSpecular', key: 'render.gouraud_specular', link: 'gouraudSpecular', group: 'shading' },
  { name: 'interpolation', key: 'render.interpolation', link: 'interpolation', group: 'shading' },
  { name: 'cull', key: 'render.cull_backfaces', link: 'cull', group: 'shading' },
  { name: 'specular', key: 'render.specular', link: 'specular', group: 'shading' },

  { name: 'polygons', key: 'render.polygons', link: 'polygons', group: 'polygons' },
  { name: 'fixedPoint', key: 'render.fixed_point_bits', link: 'fixedPoint', group: 'polygons', nullable: true, step: 1 },
  { name: 'palette.shades', key: 'render.palette_shades', link: 'palette', group: 'polygons', step: 1 },
  { name: 'palette.offset', key: 'render.palette_offset', link: 'paletteOffset', group: 'polygons', step: 1 },
  { name: 'rasterizer', key: 'render.rasterizer', link: 'rasterizer', group: 'polygons' },

  // The panels' side (render.width and render.height of each panel's scene).
  { name: 'size', link: 'size', group: 'view', kind: 'int', default: 480, min: 16, max: 2048, step: 1, choices: [240, 320, 400, 480, 560, 640, 800] },
  { name: 'background', key: 'render.background', link: 'background', group: 'view' },

  // The instruments' own controls.
  { name: 'errors', link: 'errors', group: 'instruments', kind: 'bool', default: false },
  { name: 'errorScale', link: 'errorScale', group: 'instruments', kind: 'number', default: null, nullable: true, min: 0.01, max: 1000, choices: [5, 10, 20, 25, 50, 100, 200, 255] },
  { name: 'quadAngle', link: 'quadAngle', group: 'instruments', kind: 'number', default: 30, min: -360, max: 360, slider: [0, 90], step: 1, digits: 1 },

  // What the animation saves (not part of the scene, not in the link).
  { name: 'animation.frames', group: 'animation', control: 'animation-frames', kind: 'int', default: 36, min: 4, max: 360, step: 1 },
  { name: 'animation.delay', group: 'animation', control: 'animation-delay', kind: 'int', default: 80, min: 10, max: 1000, step: 10 },
].map(fromSchema);

/** The parameter named `name` (for a light's, group 'light'). */
export function param(name, group) {
  const p = PARAMS.find((q) => q.name === name && (group === undefined ? q.group !== 'light' : q.group === group));
  if (!p) throw new Error(`no parameter ${name}`);
  return p;
}

/** Whether light `light` has parameter `p` of group 'light' (its `when`). */
export function applies(p, light) {
  return !p.when || p.when(light);
}

/** A light with every default. */
export function defaultLight() {
  const light = {};
  for (const p of PARAMS.filter((q) => q.group === 'light')) light[p.name] = structuredClone(p.default);
  return light;
}

/** Reads the value at `path` ('material.kd') of `object`. */
export function getPath(object, path) {
  return path.split('.').reduce((o, k) => (o === null || o === undefined ? o : o[k]), object);
}

/** Writes `value` at `path` of `object`, making the objects on the way. */
export function setPath(object, path, value) {
  const keys = path.split('.');
  const last = keys.pop();
  let o = object;
  for (const k of keys) {
    if (o[k] === null || typeof o[k] !== 'object') o[k] = {};
    o = o[k];
  }
  o[last] = value;
}

/** Whether `value` is a valid value of parameter `p`. */
export function valid(p, value) {
  if (value === null) return !!p.nullable;
  switch (p.kind) {
    case 'number':
      return typeof value === 'number' && Number.isFinite(value) && value >= p.min && value <= p.max;
    case 'int':
      return Number.isInteger(value) && value >= p.min && value <= p.max;
    case 'choice':
      return p.choices.includes(value);
    case 'bool':
      return typeof value === 'boolean';
    case 'rgb':
      return Array.isArray(value) && value.length === 3 && value.every((v) => Number.isInteger(v) && v >= p.min && v <= p.max);
    case 'vec3':
      return Array.isArray(value) && value.length === 3 && value.every((v) => Number.isFinite(v) && v >= p.min && v <= p.max)
        && !(p.nonzero && value.every((v) => v === 0));
    default:
      return typeof value === 'string' && value.length > 0;
  }
}

/** `value` of parameter `p` as link text (numbers rounded to `digits`, 3 by default). */
export function formatLink(p, value) {
  const round = (x) => Number(x.toFixed(p.digits ?? 3));
  switch (p.kind) {
    case 'number':
      return String(round(value));
    case 'rgb':
      return value.join(',');
    case 'vec3':
      return value.map(round).join(',');
    default:
      return String(value);
  }
}

/** Link text as a value of `p`, or undefined when it is not one. */
export function parseLink(p, text) {
  let value;
  switch (p.kind) {
    case 'number':
    case 'int':
      value = text === '' ? NaN : Number(text);
      if (p.kind === 'int' && Number.isFinite(value)) value = Math.round(value);
      break;
    case 'bool':
      value = text === 'true' ? true : text === 'false' ? false : undefined;
      break;
    case 'rgb':
    case 'vec3':
      value = text.split(',').map((s) => (s === '' ? NaN : Number(s)));
      break;
    default:
      value = text;
  }
  return value !== undefined && valid(p, value) ? value : undefined;
}
