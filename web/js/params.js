// Every parameter the page's controls set, declared once: its name (the
// path in the page's state), the key that carries it in a link, its kind,
// default, valid range and step, the span its slider covers, and the group
// of controls it belongs to. The state's defaults (state.js), the link's
// reading and writing (state.js) and the controls (form.js) are all derived
// from this table, so that it can later be read from the JSON schema the
// core provides instead of being written here.
//
// Kinds: 'number' (float), 'int', 'choice' (one of `choices`), 'bool',
// 'rgb' (three integers 0–255), 'vec3' (three numbers within ±`max`).
// `min`/`max` are the values accepted (from a number box or a link);
// `slider` is the span of the slider when it is narrower. `nullable`: null
// is a value (the model's own, or the mode off). A parameter of group
// 'light' belongs to each light of the `lights` list.

/** The groups of controls, in the order the page shows them. */
export const GROUPS = ['model', 'ambient', 'lights', 'material', 'camera', 'shading', 'polygons', 'view'];

/** The lights a scene may have in the viewer. */
export const MAX_LIGHTS = 8;

export const PARAMS = [
  // The model: its name, its tessellation (its range is the model's own).
  { name: 'model', link: 'model', group: 'model', kind: 'model', default: 'teapot' },
  { name: 'detail', link: 'detail', group: 'model', kind: 'int', default: null, nullable: true, min: 0, max: 512, step: 1 },

  { name: 'ambient.color', link: 'ambient', group: 'ambient', kind: 'rgb', default: [255, 255, 255] },
  { name: 'ambient.intensity', link: 'ambientI', group: 'ambient', kind: 'number', default: 0.2, min: 0, max: 100, slider: [0, 2], step: 0.01 },

  // Each light of the list (group 'light'); the list itself is `lights`.
  { name: 'on', link: 'on', group: 'light', kind: 'bool', default: true },
  { name: 'kind', link: 'kind', group: 'light', kind: 'choice', choices: ['point', 'directional'], default: 'point' },
  { name: 'color', link: 'light', group: 'light', kind: 'rgb', default: [255, 255, 255] },
  { name: 'intensity', link: 'lightI', group: 'light', kind: 'number', default: 1, min: 0, max: 100, slider: [0, 3], step: 0.01 },
  { name: 'position', link: 'lightPos', group: 'light', kind: 'vec3', default: [2, 2, 3], max: 1000, slider: [-10, 10], step: 0.05 },
  { name: 'direction', link: 'lightDir', group: 'light', kind: 'vec3', default: [-1, -1, -1], max: 1000, slider: [-1, 1], step: 0.01 },

  { name: 'material.ka', link: 'ka', group: 'material', kind: 'rgb', default: [200, 60, 60] },
  { name: 'material.kd', link: 'kd', group: 'material', kind: 'rgb', default: [200, 60, 60] },
  { name: 'material.ks', link: 'ks', group: 'material', kind: 'rgb', default: [255, 255, 255] },
  { name: 'material.shininess', link: 'shininess', group: 'material', kind: 'number', default: 32, min: 0, max: 10000, slider: [0, 256], step: 1 },

  { name: 'camera.yaw', link: 'yaw', group: 'camera', kind: 'number', default: 0, min: -1e6, max: 1e6, slider: [-180, 180], step: 1, wrap: 360, digits: 2 },
  { name: 'camera.pitch', link: 'pitch', group: 'camera', kind: 'number', default: 0, min: -89, max: 89, step: 1, digits: 2 },
  { name: 'camera.zoom', link: 'zoom', group: 'camera', kind: 'number', default: 1, min: 0.25, max: 8, step: 0.01 },

  { name: 'normals', link: 'normals', group: 'shading', kind: 'choice', choices: ['auto', 'file', 'uniform', 'area', 'angle'], default: 'auto' },
  { name: 'crease', link: 'crease', group: 'shading', kind: 'number', default: null, nullable: true, min: 0, max: 180, step: 1 },
  { name: 'gouraudSpecular', link: 'gouraudSpecular', group: 'shading', kind: 'bool', default: false },
  { name: 'interpolation', link: 'interpolation', group: 'shading', kind: 'choice', choices: ['perspective', 'screen'], default: 'perspective' },
  { name: 'cull', link: 'cull', group: 'shading', kind: 'bool', default: true },
  { name: 'specular', link: 'specular', group: 'shading', kind: 'choice', choices: ['phong', 'blinn-phong'], default: 'phong' },

  { name: 'polygons', link: 'polygons', group: 'polygons', kind: 'choice', choices: ['fans', 'whole'], default: 'fans' },
  { name: 'fixedPoint', link: 'fixedPoint', group: 'polygons', kind: 'int', default: null, nullable: true, on: 8, min: 1, max: 30, step: 1 },
  { name: 'palette.shades', link: 'palette', group: 'polygons', kind: 'int', default: 8, min: 2, max: 256, step: 1 },
  { name: 'palette.offset', link: 'paletteOffset', group: 'polygons', kind: 'int', default: 0, min: 0, max: 254, step: 1 },
  { name: 'rasterizer', link: 'rasterizer', group: 'polygons', kind: 'choice', choices: ['tiled', 'scanline'], default: 'tiled' },

  { name: 'size', link: 'size', group: 'view', kind: 'int', default: 480, min: 16, max: 2048, step: 1, choices: [240, 320, 400, 480, 560, 640, 800] },
  { name: 'background', link: 'background', group: 'view', kind: 'rgb', default: [0, 0, 0] },

  // The instruments' own controls.
  { name: 'errors', link: 'errors', group: 'instruments', kind: 'bool', default: false },
  { name: 'errorScale', link: 'errorScale', group: 'instruments', kind: 'number', default: null, nullable: true, min: 0.01, max: 1000, choices: [5, 10, 20, 25, 50, 100, 200, 255] },
  { name: 'quadAngle', link: 'quadAngle', group: 'instruments', kind: 'number', default: 30, min: -360, max: 360, slider: [0, 90], step: 1, digits: 1 },

  // What the animation saves (not part of the scene, not in the link).
  { name: 'animation.frames', group: 'animation', kind: 'int', default: 36, min: 4, max: 360, step: 1 },
  { name: 'animation.delay', group: 'animation', kind: 'int', default: 80, min: 10, max: 1000, step: 10 },
];

/** The parameter named `name` (for a light's, group 'light'). */
export function param(name, group) {
  const p = PARAMS.find((q) => q.name === name && (group === undefined ? q.group !== 'light' : q.group === group));
  if (!p) throw new Error(`no parameter ${name}`);
  return p;
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
      return Array.isArray(value) && value.length === 3 && value.every((v) => Number.isInteger(v) && v >= 0 && v <= 255);
    case 'vec3':
      return Array.isArray(value) && value.length === 3 && value.every((v) => Number.isFinite(v) && Math.abs(v) <= p.max);
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
