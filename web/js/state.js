// The viewer's state: one plain object holding every parameter, its
// defaults (those of `shadelab render`), the link that reproduces it, and
// the scene file (TOML) every panel renders, which is exactly what
// `shadelab render` / `shadelab compare` read.

export const METHODS = ['flat', 'gouraud', 'phong'];
export const LANGUAGES = ['en', 'ru', 'sk', 'cs'];
/** The overlays, named as `shadelab render --overlay` names them. */
export const OVERLAYS = ['wireframe', 'face-normals', 'vertex-normals', 'light'];
/** The built-in models whose exact surface is known (shadelab-lab: EXACT_MODELS). */
export const EXACT_MODELS = ['sphere', 'torus', 'cylinder', 'cone'];
export const TABS = ['about', 'inspector', 'profile', 'errors', 'overlays', 'quad', 'cost'];
/** Fixed-point fraction bits and palette sizes the renderer accepts. */
export const FIXED_POINT_BITS = [1, 30];
export const PALETTE_SHADES = [2, 256];
export const PANEL_SIZES = [240, 320, 400, 480, 560, 640, 800];
export const ZOOM_MIN = 0.25;
export const ZOOM_MAX = 8;
/** Largest file the viewer reads (crates/shadelab-wasm: MAX_FILE_BYTES). */
export const MAX_FILE_MIB = 128;
export const MESH_EXTENSIONS = ['obj', 'stl', 'ply', 'gltf', 'glb'];

export const PRESETS = {
  plastic: { ka: [255, 60, 60], kd: [255, 60, 60], ks: [255, 255, 255], shininess: 32 },
  metal: { ka: [64, 48, 16], kd: [200, 150, 50], ks: [255, 225, 140], shininess: 96 },
  chalk: { ka: [235, 235, 225], kd: [235, 235, 225], ks: [0, 0, 0], shininess: 1 },
};

/** A fresh state with every default. */
export function defaultState() {
  return {
    model: 'teapot',
    detail: null, // null: the model's default
    normals: 'auto',
    crease: null, // null: the model's default (none, or 60° for cylinder and cone)
    ambient: { color: [255, 255, 255], intensity: 0.2 },
    light: { color: [255, 255, 255], intensity: 1, position: [2, 2, 3] },
    material: { ...structuredClone(PRESETS.plastic) },
    camera: { yaw: 0, pitch: 0, zoom: 1 },
    gouraudSpecular: false,
    interpolation: 'perspective',
    cull: true,
    specular: 'phong',
    polygons: 'fans',
    rasterizer: 'tiled',
    size: 480,
    background: [0, 0, 0],
    fixedPoint: null, // fraction bits, or null: floating point
    palette: null, // {shades, offset}, or null: true colour
    // The instruments.
    pixel: null, // [x, y] under the inspector
    profile: null, // {row} or {line: [x0, y0, x1, y1]}
    errors: false, // the panels show their error against the exact surface
    errorScale: null, // the error shown brightest; null: a round number above the largest
    overlays: { flat: [], gouraud: [], phong: [] },
    quadAngle: 30,
  };
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

export const DEFAULT_LIGHT_POSITION = [2, 2, 3];

const CHOICES = {
  lang: LANGUAGES,
  tab: TABS,
  normals: ['auto', 'file', 'uniform', 'area', 'angle'],
  interpolation: ['perspective', 'screen'],
  specular: ['phong', 'blinn-phong'],
  polygons: ['fans', 'whole'],
  rasterizer: ['tiled', 'scanline'],
};

/** Which preset the material equals, or 'custom'. */
export function presetOf(material) {
  for (const [name, p] of Object.entries(PRESETS)) {
    if (['ka', 'kd', 'ks'].every((k) => p[k].every((v, i) => v === material[k][i])) && p.shininess === material.shininess) {
      return name;
    }
  }
  return 'custom';
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

/** A TOML basic string. JSON's escapes are TOML's, but for DEL. */
export function tomlString(s) {
  return JSON.stringify(s).replace(/\x7f/g, '\\u007f');
}

/**
 * The scene file for `state`: with `method` ('flat' | 'gouraud' | 'phong')
 * the scene one panel renders; without, the scene `shadelab compare` reads.
 */
export function sceneToml(state, method) {
  const lines = ['[model]', `source = ${tomlString(state.model)}`];
  if (state.detail !== null) lines.push(`detail = ${Math.round(state.detail)}`);
  lines.push(`normals = "${state.normals}"`);
  if (state.crease !== null) lines.push(`crease_angle = ${float(state.crease)}`);
  lines.push(
    '',
    '[ambient]',
    `color = ${rgb(state.ambient.color)}`,
    `intensity = ${float(state.ambient.intensity)}`,
    '',
    '[[lights]]',
    'kind = "point"',
    `position = ${vec3(state.light.position)}`,
    `color = ${rgb(state.light.color)}`,
    `intensity = ${float(state.light.intensity)}`,
    '',
    '[material]',
    `ka = ${rgb(state.material.ka)}`,
    `kd = ${rgb(state.material.kd)}`,
    `ks = ${rgb(state.material.ks)}`,
    `shininess = ${float(state.material.shininess)}`,
    '',
    '[render]',
    `width = ${state.size}`,
    `height = ${state.size}`,
  );
  if (method) lines.push(`shading = "${method}"`);
  lines.push(
    `background = ${rgb(state.background)}`,
    `cull_backfaces = ${state.cull}`,
    `gouraud_specular = ${state.gouraudSpecular}`,
    `interpolation = "${state.interpolation}"`,
    `rasterizer = "${rasterizerOf(state)}"`,
    `polygons = "${state.polygons}"`,
    `specular = "${state.specular}"`,
  );
  if (state.fixedPoint !== null) lines.push(`fixed_point_bits = ${Math.round(state.fixedPoint)}`);
  if (state.palette !== null) {
    lines.push(`palette_shades = ${Math.round(state.palette.shades)}`, `palette_offset = ${Math.round(state.palette.offset)}`);
  }
  lines.push(
    `yaw = ${float(state.camera.yaw)}`,
    `pitch = ${float(state.camera.pitch)}`,
    `zoom = ${float(state.camera.zoom)}`,
    '',
  );
  return lines.join('\n');
}

// ---- the link ----

const round = (x, digits = 3) => Number(x.toFixed(digits));

/** The state's (and the view's) differences from the defaults, as URL parameters (after `#`). */
export function toHash(state, view = defaultView()) {
  const d = defaultState();
  const p = new URLSearchParams();
  const put = (key, value, def) => {
    if (JSON.stringify(value) !== JSON.stringify(def)) p.set(key, Array.isArray(value) ? value.join(',') : String(value));
  };
  put('model', state.model, d.model);
  put('detail', state.detail, d.detail);
  put('normals', state.normals, d.normals);
  put('crease', state.crease, d.crease);
  put('ambient', state.ambient.color, d.ambient.color);
  put('ambientI', round(state.ambient.intensity), d.ambient.intensity);
  put('light', state.light.color, d.light.color);
  put('lightI', round(state.light.intensity), d.light.intensity);
  put('lightPos', state.light.position.map((v) => round(v)), d.light.position);
  put('ka', state.material.ka, d.material.ka);
  put('kd', state.material.kd, d.material.kd);
  put('ks', state.material.ks, d.material.ks);
  put('shininess', round(state.material.shininess), d.material.shininess);
  put('yaw', round(state.camera.yaw, 2), d.camera.yaw);
  put('pitch', round(state.camera.pitch, 2), d.camera.pitch);
  put('zoom', round(state.camera.zoom), d.camera.zoom);
  put('gouraudSpecular', state.gouraudSpecular, d.gouraudSpecular);
  put('interpolation', state.interpolation, d.interpolation);
  put('cull', state.cull, d.cull);
  put('specular', state.specular, d.specular);
  put('polygons', state.polygons, d.polygons);
  put('rasterizer', state.rasterizer, d.rasterizer);
  put('size', state.size, d.size);
  put('background', state.background, d.background);
  put('fixedPoint', state.fixedPoint, d.fixedPoint);
  if (state.palette !== null) {
    p.set('palette', String(state.palette.shades));
    if (state.palette.offset) p.set('paletteOffset', String(state.palette.offset));
  }
  put('pixel', state.pixel, d.pixel);
  if (state.profile?.line) p.set('line', state.profile.line.map((v) => round(v, 1)).join(','));
  else if (state.profile) p.set('row', String(state.profile.row));
  put('errors', state.errors, d.errors);
  put('errorScale', state.errorScale, d.errorScale);
  for (const m of METHODS) {
    if (state.overlays[m].length) p.set(`overlays.${m}`, state.overlays[m].join(','));
  }
  put('quadAngle', round(state.quadAngle, 1), d.quadAngle);
  const dv = defaultView();
  put('lang', view.lang, dv.lang);
  put('tab', view.tab, dv.tab);
  const s = p.toString();
  return s ? `#${s}` : '';
}

/**
 * The state and view a link describes, and the keys whose values were
 * invalid (left at their defaults). A model name that is not built in is a
 * user's file, which the link names but cannot carry.
 */
export function fromHash(hash) {
  const state = defaultState();
  const view = defaultView();
  const invalid = [];
  const p = new URLSearchParams(hash.replace(/^#/, ''));
  const num = (key, min, max, apply) => {
    if (!p.has(key)) return;
    const v = Number(p.get(key));
    if (p.get(key) !== '' && Number.isFinite(v) && v >= min && v <= max) apply(v);
    else invalid.push(key);
  };
  const color = (key, apply) => {
    if (!p.has(key)) return;
    const parts = p.get(key).split(',').map(Number);
    if (parts.length === 3 && parts.every((v) => Number.isInteger(v) && v >= 0 && v <= 255)) apply(parts);
    else invalid.push(key);
  };
  const choice = (key, apply) => {
    if (!p.has(key)) return;
    const v = p.get(key);
    const allowed = CHOICES[key] ?? ['true', 'false'];
    if (allowed.includes(v)) apply(v);
    else invalid.push(key);
  };
  if (p.has('model')) state.model = p.get('model');
  num('detail', 0, 512, (v) => (state.detail = Math.round(v)));
  choice('normals', (v) => (state.normals = v));
  num('crease', 0, 180, (v) => (state.crease = v));
  color('ambient', (v) => (state.ambient.color = v));
  num('ambientI', 0, 100, (v) => (state.ambient.intensity = v));
  color('light', (v) => (state.light.color = v));
  num('lightI', 0, 100, (v) => (state.light.intensity = v));
  if (p.has('lightPos')) {
    const v = p.get('lightPos').split(',').map(Number);
    if (v.length === 3 && v.every((x) => Number.isFinite(x) && Math.abs(x) <= 1000)) state.light.position = v;
    else invalid.push('lightPos');
  }
  color('ka', (v) => (state.material.ka = v));
  color('kd', (v) => (state.material.kd = v));
  color('ks', (v) => (state.material.ks = v));
  num('shininess', 0, 10000, (v) => (state.material.shininess = v));
  num('yaw', -1e6, 1e6, (v) => (state.camera.yaw = v));
  num('pitch', -89, 89, (v) => (state.camera.pitch = v));
  num('zoom', ZOOM_MIN, ZOOM_MAX, (v) => (state.camera.zoom = v));
  choice('gouraudSpecular', (v) => (state.gouraudSpecular = v === 'true'));
  choice('interpolation', (v) => (state.interpolation = v));
  choice('cull', (v) => (state.cull = v === 'true'));
  choice('specular', (v) => (state.specular = v));
  choice('polygons', (v) => (state.polygons = v));
  choice('rasterizer', (v) => (state.rasterizer = v));
  num('size', 16, 2048, (v) => (state.size = Math.round(v)));
  color('background', (v) => (state.background = v));
  const integers = (key, count, min, max) => {
    if (!p.has(key)) return null;
    const v = p.get(key).split(',').map(Number);
    if (v.length === count && v.every((x) => Number.isInteger(x) && x >= min && x <= max)) return v;
    invalid.push(key);
    return null;
  };
  num('fixedPoint', FIXED_POINT_BITS[0], FIXED_POINT_BITS[1], (v) => (state.fixedPoint = Math.round(v)));
  num('palette', PALETTE_SHADES[0], PALETTE_SHADES[1], (v) => (state.palette = { shades: Math.round(v), offset: 0 }));
  num('paletteOffset', 0, 254, (v) => {
    if (state.palette && state.palette.shades + Math.round(v) <= 256) state.palette.offset = Math.round(v);
    else invalid.push('paletteOffset');
  });
  const pixel = integers('pixel', 2, 0, 2047);
  if (pixel) state.pixel = pixel;
  const row = integers('row', 1, 0, 2047);
  if (row) state.profile = { row: row[0] };
  if (p.has('line')) {
    const v = p.get('line').split(',').map(Number);
    if (v.length === 4 && v.every((x) => Number.isFinite(x) && Math.abs(x) <= 1e4)) state.profile = { line: v };
    else invalid.push('line');
  }
  choice('errors', (v) => (state.errors = v === 'true'));
  num('errorScale', 0.01, 1000, (v) => (state.errorScale = v));
  for (const m of METHODS) {
    const key = `overlays.${m}`;
    if (!p.has(key)) continue;
    const names = p.get(key).split(',').filter(Boolean);
    if (names.every((n) => OVERLAYS.includes(n))) state.overlays[m] = OVERLAYS.filter((n) => names.includes(n));
    else invalid.push(key);
  }
  num('quadAngle', -360, 360, (v) => (state.quadAngle = v));
  choice('lang', (v) => (view.lang = v));
  choice('tab', (v) => (view.tab = v));
  // A pixel or row outside the panels is dropped.
  if (state.pixel && state.pixel.some((v) => v >= state.size)) state.pixel = null;
  if (state.profile?.row !== undefined && state.profile.row >= state.size) state.profile = null;
  return { state, view, invalid };
}
