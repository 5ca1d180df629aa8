// The viewer's state: one plain object holding every parameter, its
// defaults (those of `shadelab render`), the link that reproduces it, and
// the scene file (TOML) every panel renders, which is exactly what
// `shadelab render` / `shadelab compare` read.

import { PARAMS, METHODS, MAX_LIGHTS, param, applies, defaultLight, getPath, setPath, valid, formatLink, parseLink } from './params.js';

export { METHODS, MAX_LIGHTS, defaultLight };
export const LANGUAGES = ['en', 'ru', 'sk', 'cs'];
/** The overlays, named as `shadelab render --overlay` names them. */
export const OVERLAYS = ['wireframe', 'face-normals', 'vertex-normals', 'light'];
/** The built-in models whose exact surface is known (shadelab-lab: EXACT_MODELS). */
export const EXACT_MODELS = ['sphere', 'torus', 'cylinder', 'cone'];
export const TABS = ['about', 'inspector', 'profile', 'errors', 'overlays', 'quad', 'cost'];
export const ZOOM_MIN = param('camera.zoom').min;
export const ZOOM_MAX = param('camera.zoom').max;
/** Largest file the viewer reads (crates/shadelab-wasm: MAX_FILE_BYTES). */
export const MAX_FILE_MIB = 128;
export const MESH_EXTENSIONS = ['obj', 'stl', 'ply', 'gltf', 'glb'];

export const PRESETS = {
  // The default material (params.js).
  plastic: Object.fromEntries(['ka', 'kd', 'ks', 'shininess'].map((k) => [k, param(`material.${k}`).default])),
  metal: { ka: [64, 48, 16], kd: [200, 150, 50], ks: [255, 225, 140], shininess: 96 },
  chalk: { ka: [235, 235, 225], kd: [235, 235, 225], ks: [0, 0, 0], shininess: 1 },
};

/** The parameters kept as they are in the state and the link (the rest have their own code below). */
const PLAIN = PARAMS.filter((p) => p.link && p.group !== 'light' && p.group !== 'animation' && !p.name.startsWith('palette.') && p.name !== 'model');

/** A light's parameters of the scene (group 'light' with a scene-file key), in the page's order. */
const LIGHT = PARAMS.filter((p) => p.group === 'light' && p.key);
/**
 * A light's fields in a `lights=` link: those every such link has
 * (`inEveryLink`) in the core's table's order, then those added since in
 * the page's order, so that a parameter declared last in params.js comes
 * last in the link and older links keep their meaning.
 */
const LIGHT_FIELDS = [...LIGHT.filter((p) => p.inEveryLink).sort((a, b) => a.order - b.order), ...LIGHT.filter((p) => !p.inEveryLink)];

/** A fresh state with every default (params.js). */
export function defaultState() {
  const state = {};
  for (const p of PARAMS) {
    if (p.group !== 'light' && !p.name.startsWith('palette.')) setPath(state, p.name, structuredClone(p.default));
  }
  state.lights = [defaultLight()];
  state.palette = null; // {shades, offset}, or null: true colour
  // The instruments.
  state.pixel = null; // [x, y] under the inspector
  state.profile = null; // {row} or {line: [x0, y0, x1, y1]}
  state.overlays = { flat: [], gouraud: [], phong: [] };
  return state;
}

/** What the page remembers apart from the scene: kept by Reset all. */
export function defaultView() {
  return { lang: null, tab: 'about' };
}

/** Whether the scene needs the scanline rasterizer (whole polygons, fixed point, palette). */
export function needsScanline(state) {
  return state.polygons === 'whole' || state.fixedPoint !== null || state.palette !== null;
}

/** The rasterizer that draws: the one chosen, unless a mode needs the scanline one. */
export function rasterizerOf(state) {
  return needsScanline(state) ? 'scanline' : state.rasterizer;
}

/** Whether the model has an exact surface to compare with. */
export function hasExactSurface(state) {
  return EXACT_MODELS.includes(state.model);
}

export const DEFAULT_LIGHT_POSITION = param('position', 'light').default;

/** Which preset the material equals, or 'custom'. */
export function presetOf(material) {
  for (const [name, p] of Object.entries(PRESETS)) {
    if (['ka', 'kd', 'ks'].every((k) => p[k].every((v, i) => v === material[k][i])) && p.shininess === material.shininess) {
      return name;
    }
  }
  return 'custom';
}

/** A light switched to `kind`, its vector turned into the other kind's: it lights from the same side. */
export function withKind(light, kind) {
  if (light.kind === kind) return light;
  const unit = (v) => {
    const n = Math.hypot(...v) || 1;
    return v.map((x) => x / n);
  };
  const round = (v) => v.map((x) => Number(x.toFixed(3)));
  if (kind === 'directional') {
    return { ...light, kind, direction: round(unit(light.position).map((x) => -x)) };
  }
  const distance = Math.hypot(...light.position) || Math.hypot(...DEFAULT_LIGHT_POSITION);
  return { ...light, kind, position: round(unit(light.direction).map((x) => -x * distance)) };
}

// ---- numbers as TOML ----

function float(x) {
  if (!Number.isFinite(x)) throw new Error(`not a finite number: ${x}`);
  const s = String(x);
  return /[.eE]/.test(s) ? s : `${s}.0`;
}

function rgb(c) {
  return `[${c.map((v) => Math.round(v)).join(', ')}]`;
}

function vec3(v) {
  return `[${v.map(float).join(', ')}]`;
}

/** Parameter `p`'s line in the scene file: its key in its table, and `value` as its kind is written. */
function line(p, value) {
  const key = p.key.slice(p.key.indexOf('.') + 1);
  switch (p.kind) {
    case 'number':
      return `${key} = ${float(value)}`;
    case 'int':
      return `${key} = ${Math.round(value)}`;
    case 'rgb':
      return `${key} = ${rgb(value)}`;
    case 'vec3':
      return `${key} = ${vec3(value)}`;
    case 'bool':
      return `${key} = ${value}`;
    default:
      return `${key} = ${tomlString(value)}`;
  }
}

/**
 * The lines of table `table` ('material') that `lines`, its lines written
 * by hand, do not set (read from them): each parameter of the table that
 * `object` (the state, a light) has and that is not null, in the core's
 * table's order. A light has those its kind has (`when`). So a new
 * parameter has its line with no code of its own.
 */
function rest(table, object, lines = []) {
  const written = new Set(lines.map((l) => l.split(' = ')[0]));
  return PARAMS
    .filter((p) => p.key?.startsWith(`${table}.`) && applies(p, object) && !written.has(p.key.slice(table.length + 1)))
    .sort((a, b) => a.order - b.order)
    .flatMap((p) => {
      const value = getPath(object, p.name);
      return value === null || value === undefined ? [] : [line(p, value)];
    });
}

/** A TOML basic string. JSON's escapes are TOML's, but for DEL. */
export function tomlString(s) {
  return JSON.stringify(s).replace(/\x7f/g, '\\u007f');
}

/**
 * The scene file for `state`: with `method` ('flat' | 'gouraud' | 'phong')
 * the scene one panel renders; without, the scene `shadelab compare` reads.
 */
export function sceneToml(state, method) {
  const on = state.lights.filter((l) => l.on);
  // With every light off, an empty list: no [[lights]] at all would mean the default light.
  const lines = on.length ? [] : ['lights = []', ''];
  // The model by hand: its normals, which the page chooses and the table has not, sit among the table's keys.
  const model = [`source = ${tomlString(state.model)}`];
  if (state.detail !== null) model.push(`detail = ${Math.round(state.detail)}`);
  model.push(`normals = "${state.normals}"`);
  if (state.crease !== null) model.push(`crease_angle = ${float(state.crease)}`);
  lines.push('[model]', ...model, ...rest('model', state, model), '');
  lines.push('[ambient]', ...rest('ambient', state), '');
  for (const l of on) {
    const kind = [`kind = "${l.kind}"`];
    lines.push('[[lights]]', ...kind, ...rest('lights', l, kind), '');
  }
  lines.push('[material]', ...rest('material', state), '');
  // The panel's size, its method, the rasterizer that draws and the palette are the page's own: by hand.
  const render = [`width = ${state.size}`, `height = ${state.size}`];
  if (method) render.push(`shading = "${method}"`);
  render.push(
    `background = ${rgb(state.background)}`,
    `cull_backfaces = ${state.cull}`,
    `gouraud_specular = ${state.gouraudSpecular}`,
    `interpolation = "${state.interpolation}"`,
    `rasterizer = "${rasterizerOf(state)}"`,
    `polygons = "${state.polygons}"`,
    `specular = "${state.specular}"`,
  );
  if (state.fixedPoint !== null) render.push(`fixed_point_bits = ${Math.round(state.fixedPoint)}`);
  if (state.palette !== null) {
    render.push(`palette_shades = ${Math.round(state.palette.shades)}`, `palette_offset = ${Math.round(state.palette.offset)}`);
  }
  render.push(
    `yaw = ${float(state.camera.yaw)}`,
    `pitch = ${float(state.camera.pitch)}`,
    `zoom = ${float(state.camera.zoom)}`,
  );
  lines.push('[render]', ...render, ...rest('render', state, render), '');
  return lines.join('\n');
}

// ---- the link ----

const round = (x, digits = 3) => Number(x.toFixed(digits));

/**
 * A light in a link: its kind, then the fields (LIGHT_FIELDS) its kind has
 * (kind:x,y,z:r,g,b:intensity, then a point light's attenuation k0,k1,k2),
 * and :off when it is off. A field that links made before it lack (not
 * `inEveryLink`) is left out, from the end, while it is at its default.
 */
function lightToLink(l) {
  const fields = LIGHT_FIELDS.filter((q) => applies(q, l));
  const texts = fields.map((q) => formatLink(q, l[q.name]));
  const d = defaultLight();
  while (fields.length && !fields.at(-1).inEveryLink && texts.at(-1) === formatLink(fields.at(-1), d[fields.at(-1).name])) {
    fields.pop();
    texts.pop();
  }
  return [l.kind, ...texts, ...(l.on ? [] : ['off'])].join(':');
}

function lightFromLink(text) {
  const [kind, ...parts] = text.split(':');
  const light = defaultLight();
  light.kind = parseLink(param('kind', 'light'), kind);
  if (light.kind === undefined) return undefined;
  const fields = LIGHT_FIELDS.filter((q) => applies(q, light));
  const always = fields.filter((q) => q.inEveryLink).length;
  const off = parts.length > always && parts.at(-1) === 'off';
  const values = off ? parts.slice(0, -1) : parts;
  if (values.length < always || values.length > fields.length) return undefined;
  for (const [i, v] of values.entries()) {
    light[fields[i].name] = parseLink(fields[i], v);
    if (light[fields[i].name] === undefined) return undefined;
  }
  light.on = !off;
  return light;
}

/** Whether the lights are one point light that is on: the link then uses the keys it always had. */
const singlePointLight = (lights) => lights.length === 1 && lights[0].kind === 'point' && lights[0].on;

/** The state's (and the view's) differences from the defaults, as URL parameters (after `#`). */
export function toHash(state, view = defaultView()) {
  const d = defaultState();
  const p = new URLSearchParams();
  const put = (key, value, def, text) => {
    if (JSON.stringify(value) !== JSON.stringify(def)) p.set(key, text ?? (Array.isArray(value) ? value.join(',') : String(value)));
  };
  put('model', state.model, d.model);
  for (const q of PLAIN) {
    const value = getPath(state, q.name);
    const def = getPath(d, q.name);
    if (value === null || value === undefined) put(q.link, value, def, '');
    else if (JSON.stringify(value) !== JSON.stringify(def)) p.set(q.link, formatLink(q, value));
  }
  if (singlePointLight(state.lights)) {
    const [l] = state.lights;
    const [dl] = d.lights;
    for (const q of LIGHT.filter((q) => applies(q, l))) {
      if (formatLink(q, l[q.name]) !== formatLink(q, dl[q.name])) p.set(q.link, formatLink(q, l[q.name]));
    }
  } else {
    p.set('lights', state.lights.map(lightToLink).join(';'));
  }
  if (state.palette !== null) {
    p.set('palette', String(state.palette.shades));
    if (state.palette.offset) p.set('paletteOffset', String(state.palette.offset));
  }
  put('pixel', state.pixel, d.pixel);
  if (state.profile?.line) p.set('line', state.profile.line.map((v) => round(v, 1)).join(','));
  else if (state.profile) p.set('row', String(state.profile.row));
  for (const m of METHODS) {
    if (state.overlays[m].length) p.set(`overlays.${m}`, state.overlays[m].join(','));
  }
  const dv = defaultView();
  put('lang', view.lang, dv.lang);
  put('tab', view.tab, dv.tab);
  const s = p.toString();
  return s ? `#${s}` : '';
}

/**
 * The state and view a link describes, and the keys whose values were
 * invalid (left at their defaults). A model name that is not built in is a
 * user's file, which the link names but cannot carry. Links written before
 * the page had several lights (`light`, `lightI`, `lightPos`) set the first.
 */
export function fromHash(hash) {
  const state = defaultState();
  const view = defaultView();
  const invalid = [];
  const p = new URLSearchParams(hash.replace(/^#/, ''));
  const read = (q, key, apply) => {
    if (!p.has(key)) return;
    const v = parseLink(q, p.get(key));
    if (v === undefined) invalid.push(key);
    else apply(v);
  };
  if (p.has('model')) state.model = p.get('model');
  for (const q of PLAIN) read(q, q.link, (v) => setPath(state, q.name, v));
  if (p.has('lights')) {
    const lights = p.get('lights') === '' ? [] : p.get('lights').split(';').map(lightFromLink);
    if (lights.length <= MAX_LIGHTS && !lights.includes(undefined)) state.lights = lights;
    else invalid.push('lights');
  } else {
    for (const q of LIGHT.filter((q) => applies(q, state.lights[0]))) read(q, q.link, (v) => (state.lights[0][q.name] = v));
  }
  const shades = param('palette.shades');
  read(shades, 'palette', (v) => (state.palette = { shades: v, offset: 0 }));
  read(param('palette.offset'), 'paletteOffset', (v) => {
    if (state.palette && state.palette.shades + v <= shades.max) state.palette.offset = v;
    else invalid.push('paletteOffset');
  });
  const integers = (key, count, min, max) => {
    if (!p.has(key)) return null;
    const v = p.get(key).split(',').map(Number);
    if (v.length === count && v.every((x) => Number.isInteger(x) && x >= min && x <= max)) return v;
    invalid.push(key);
    return null;
  };
  const pixel = integers('pixel', 2, 0, 2047);
  if (pixel) state.pixel = pixel;
  const row = integers('row', 1, 0, 2047);
  if (row) state.profile = { row: row[0] };
  if (p.has('line')) {
    const v = p.get('line').split(',').map(Number);
    if (v.length === 4 && v.every((x) => Number.isFinite(x) && Math.abs(x) <= 1e4)) state.profile = { line: v };
    else invalid.push('line');
  }
  for (const m of METHODS) {
    const key = `overlays.${m}`;
    if (!p.has(key)) continue;
    const names = p.get(key).split(',').filter(Boolean);
    if (names.every((n) => OVERLAYS.includes(n))) state.overlays[m] = OVERLAYS.filter((n) => names.includes(n));
    else invalid.push(key);
  }
  const choice = (key, allowed, apply) => {
    if (!p.has(key)) return;
    if (allowed.includes(p.get(key))) apply(p.get(key));
    else invalid.push(key);
  };
  choice('lang', LANGUAGES, (v) => (view.lang = v));
  choice('tab', TABS, (v) => (view.tab = v));
  // A pixel or row outside the panels is dropped.
  if (state.pixel && state.pixel.some((v) => v >= state.size)) state.pixel = null;
  if (state.profile?.row !== undefined && state.profile.row >= state.size) state.profile = null;
  return { state, view, invalid };
}
