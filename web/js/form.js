// The column of controls beside the panels: every parameter of the scene the
// three panels render, group by group. The ordinary parameters come from the
// table of parameters (params.js), each with the control its kind has, in
// the order declared there: its range, step, default, label and control
// name are derived from its entry. The few that need more (the model, the normals,
// fixed point, the palette, the rasterizer, the panel size, a light's
// switch and kind) and what is not a parameter (the material preset, the
// drag mode, the file, the explanations) are written here by hand, in
// their place. controls.js builds the controls. Built again when the
// language changes.
import { t, lab, translation } from './i18n.js';
import { el } from './dom.js';
import { Controls } from './controls.js';
import { PARAMS, param, applies, getPath, setPath, MAX_LIGHTS } from './params.js';
import {
  PRESETS, MAX_FILE_MIB, MESH_EXTENSIONS, presetOf, needsScanline, rasterizerOf, defaultLight, withKind,
} from './state.js';

/** A range control's span, step and accepted values, from the parameter's declaration. */
function spanOf(p) {
  const [min, max] = p.slider ?? [p.min, p.max];
  return { min, max, step: p.step, accept: [p.min, p.max] };
}

/** The key of a parameter's label in the string tables: param.<scene key>, and .<part> or .<choice>. */
const labelKey = (p, sub) => ['param', p.key ?? p.name, ...(sub === undefined ? [] : [sub])].join('.');

/**
 * A parameter's label (of its part `part`) in the page's language: its
 * translation, else the English label of the core's table ("Fall-off:
 * constant"), so that a new parameter needs no string of its own.
 */
export function labelOf(p, part) {
  const fallback = p.label === undefined ? undefined : part === undefined ? p.label : `${p.label}: ${part}`;
  return translation(labelKey(p, part)) ?? fallback ?? t(labelKey(p, part));
}

/** The label of choice `value` of parameter `p`: its translation, else its name. */
export function optionLabel(p, value) {
  return translation(labelKey(p, value)) ?? value;
}

/**
 * The name of parameter `p`'s control (of its part `part`): its `control`,
 * else its name within its group in kebab case ('ka', 'gouraud-specular'),
 * after `prefix` ('light-1-color', 'light-1-attenuation-constant').
 */
export function controlName(p, prefix, part) {
  const own = p.name.startsWith(`${p.group}.`) ? p.name.slice(p.group.length + 1) : p.name;
  const name = p.control ?? own.replace(/\./g, '-').replace(/[A-Z]/g, (c) => `-${c.toLowerCase()}`);
  return [prefix, name, part].filter(Boolean).join('-');
}

/** The names of parameter `p`'s controls: one per part of a vector. */
export function controlNames(p, prefix) {
  return p.kind === 'vec3' ? p.parts.map((part) => controlName(p, prefix, part)) : [controlName(p, prefix)];
}

/**
 * The control of parameter `p`, from its kind: a number a slider with its
 * number box, an rgb colour three boxes and a picker, a vector a slider per
 * part, a bool a checkbox, a choice a select. It reads and writes the value
 * at `p.name` of `of()` (the state, a light); `prefix` goes before its name.
 */
export function paramControl(c, parent, p, { of, prefix }) {
  const name = controlName(p, prefix);
  const label = labelOf(p);
  const get = () => getPath(of(), p.name);
  const set = (v) => setPath(of(), p.name, v);
  switch (p.kind) {
    case 'number':
    case 'int': {
      const round = p.kind === 'int' ? Math.round : (v) => v;
      if (!p.wrap) return c.range(parent, { name, label, ...spanOf(p), get, set: (v) => set(round(v)) });
      // An angle that wraps shows within one turn around 0, and its number box takes the slider's span.
      const half = p.wrap / 2;
      return c.range(parent, {
        name, label, ...spanOf(p), accept: p.slider,
        get: () => ((((get() + half) % p.wrap) + p.wrap) % p.wrap) - half, set: (v) => set(round(v)),
      });
    }
    case 'rgb':
      return c.rgb(parent, { name, label, get, set });
    case 'vec3':
      return p.parts.map((part, i) => c.range(parent, {
        name: controlName(p, prefix, part), label: labelOf(p, part), ...spanOf(p),
        get: () => get()[i],
        set: (v) => {
          const next = [...get()];
          next[i] = v;
          // A vector that may not be zero (a direction) keeps the last that was not.
          if (p.nonzero && next.every((x) => x === 0)) return;
          set(next);
        },
      }));
    case 'bool':
      return c.checkbox(parent, { name, label, get, set });
    case 'choice':
      return c.select(parent, { name, label, options: () => p.choices.map((v) => [v, optionLabel(p, v)]), get, set });
    default:
      throw new Error(`no control for ${p.name} (${p.kind})`);
  }
}

/** The colour a light's marker and swatch are drawn in: its colour, never black. */
export function lightSwatch(light) {
  const [r, g, b] = light.color;
  const m = Math.max(r, g, b, 1);
  const k = m < 96 ? 96 / m : 1;
  return `rgb(${Math.round(r * k)}, ${Math.round(g * k)}, ${Math.round(b * k)})`;
}

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
  /**
   * Each parameter of `group` into `parent`, in the order of params.js:
   * its own control, or `special[name](p)` where it needs more (null: made
   * with another's).
   */
  const params = (parent, group, special = {}) => {
    for (const p of PARAMS.filter((q) => q.group === group)) {
      if (special[p.name]) special[p.name](p);
      else if (!(p.name in special)) paramControl(c, parent, p, { of: s });
    }
  };

  const model = c.group('group.model', 'model');
  params(model, 'model', {
    model: () => c.select(model, {
      name: 'model',
      label: t('model.source'),
      options: () => [
        ...page.models().map((m) => [m.name, modelName(m.name)]),
        ...(page.userFile() ? [[page.userFile().name, page.userFile().name]] : []),
      ],
      get: () => s().model,
      // Another model is framed: the camera starts again (the control's change re-renders).
      set: (v) => page.setModel(v, false),
    }),
    // Each model has its own range of detail, and the model's own default.
    detail: () => c.range(model, {
      name: 'detail',
      label: t('model.detail'),
      min: () => page.modelInfo()?.detail_min ?? 0,
      max: () => page.modelInfo()?.detail_max ?? 1,
      step: 1,
      get: () => s().detail ?? page.modelInfo()?.default_detail ?? 0,
      set: (v) => (s().detail = Math.round(v)),
      hint: () => (page.modelInfo() ? t(`model.detailMeaning.${page.modelInfo().name}`) : ''),
      visible: () => page.modelInfo() !== null,
    }),
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
  params(ambient, 'ambient');

  // The lights: a block per light, rebuilt when lights are added, removed or change kind.
  const lightsBox = c.group('group.lights', 'lights');
  const lightsBody = el('div', { class: 'lights' });
  lightsBox.append(lightsBody);
  let built = null;
  let lightControls = null;
  const shape = () => s().lights.map((l) => l.kind).join(',');
  const buildLights = () => {
    lightsBody.replaceChildren();
    built = shape();
    lightControls = new Controls(lightsBody, page.changed);
    const lc = lightControls;
    s().lights.forEach((_, k) => {
      const L = () => s().lights[k];
      const n = k + 1;
      const block = el('div', { class: 'light', 'data-light': String(k) });
      lightsBody.append(block);
      block.addEventListener('focusin', () => page.setActiveLight(k));
      // The light's parameters its kind has (`when`); its switch heads the block, with its swatch and Remove.
      for (const p of PARAMS.filter((q) => q.group === 'light' && applies(q, L()))) {
        if (p.name === 'on') {
          const head = el('div', { class: 'light-head' });
          block.append(head);
          head.append(el('span', { class: 'swatch light-swatch', 'aria-hidden': 'true' }));
          lc.onRefresh(() => head.firstChild.style.setProperty('background', lightSwatch(L())));
          head.firstChild.style.setProperty('background', lightSwatch(L()));
          lc.checkbox(head, { name: controlName(p, `light-${n}`), label: t('lights.on', { n }), get: () => L().on, set: (v) => (L().on = v) });
          const remove = el('button', { type: 'button', class: 'light-remove', text: t('lights.remove'), 'aria-label': t('lights.remove.label', { n }) });
          remove.addEventListener('click', () => {
            s().lights.splice(k, 1);
            page.changed();
          });
          head.append(remove);
        } else if (p.name === 'kind') {
          // Another kind turns the light's vector into the other kind's (and rebuilds the block).
          lc.select(block, {
            name: controlName(p, `light-${n}`), label: t('lights.kind'),
            options: () => options('lights.kind', p.choices),
            get: () => L().kind,
            set: (v) => (s().lights[k] = withKind(L(), v)),
          });
        } else {
          paramControl(lc, block, p, { of: L, prefix: `light-${n}` });
        }
      }
    });
    const add = el('button', { type: 'button', class: 'light-add', text: t('lights.add'), disabled: s().lights.length >= MAX_LIGHTS });
    add.addEventListener('click', () => {
      // A new light comes from the other side, dimmer, so that it shows.
      const light = defaultLight();
      const k = s().lights.length;
      light.position = [[-2, 1, 2], [0, 3, -2], [2, -2, 2], [-3, -1, -2]][k % 4];
      light.intensity = 0.6;
      s().lights.push(light);
      page.setActiveLight(k);
      page.changed();
    });
    lightsBody.append(el('div', { class: 'row' }, [add]), el('p', { class: 'hint', text: t('lights.hint', { max: MAX_LIGHTS }) }));
  };
  buildLights();
  c.onRefresh(() => {
    if (shape() !== built) {
      const focused = document.activeElement?.name;
      buildLights();
      if (focused) lightsBody.querySelector(`[name="${focused}"]`)?.focus();
    } else {
      lightControls.refresh();
    }
  });

  const material = c.group('group.material', 'material');
  c.select(material, {
    name: 'preset',
    label: t('material.preset'),
    options: () => [['custom', t('material.preset.custom'), true], ...Object.keys(PRESETS).map((p) => [p, t(`material.preset.${p}`)])],
    get: () => presetOf(s().material),
    set: (v) => { if (PRESETS[v]) s().material = structuredClone(PRESETS[v]); },
  });
  params(material, 'material');

  const camera = c.group('group.camera', 'camera');
  params(camera, 'camera');
  c.select(camera, {
    name: 'drag', label: t('camera.drag'), options: () => options('camera.drag', ['camera', 'light']),
    get: () => page.dragMode(), set: (v) => page.setDragMode(v),
  });
  c.button(camera, { label: t('camera.reset'), onclick: page.resetCamera });
  c.note(camera, () => t('camera.help'));

  const shading = c.group('group.shading', 'shading');
  params(shading, 'shading', {
    // 'file' only for a loaded file that has normals.
    normals: (p) => c.select(shading, {
      name: 'normals', label: t('shading.normals'),
      options: () => options('shading.normals', p.choices).map(([v, l]) => {
        const file = page.userFile();
        return [v, l, v === 'file' && !(file && s().model === file.name && file.has_normals)];
      }),
      get: () => s().normals, set: (v) => (s().normals = v),
    }),
    // Null is the model's own angle, which the slider shows.
    crease: (p) => c.range(shading, {
      name: 'crease', label: t('shading.crease'), ...spanOf(p),
      get: () => s().crease ?? page.modelInfo()?.default_crease ?? 180, set: (v) => (s().crease = v),
      hint: () => t('shading.crease.hint'),
    }),
    interpolation: (p) => {
      paramControl(c, shading, p, { of: s });
      c.details(shading, { summary: t('explain.summary'), text: () => lab(`about.interpolation_${s().interpolation}`) });
    },
    specular: (p) => {
      paramControl(c, shading, p, { of: s });
      c.note(shading, () => t(`shading.specular.${s().specular}.hint`));
      c.details(shading, { summary: t('shading.specular.explain'), text: () => lab('about.blinn') });
    },
  });

  // Interpolation on polygons, and the modes of old hardware: all drawn by the scanline rasterizer.
  const polygons = c.group('group.polygons', 'polygons');
  params(polygons, 'polygons', {
    polygons: (p) => {
      paramControl(c, polygons, p, { of: s });
      c.details(polygons, { summary: t('explain.summary'), text: () => lab(`about.polygons_${s().polygons}`) });
    },
    // A mode switched on and off, its bits shown while it is on.
    fixedPoint: (p) => {
      c.checkbox(polygons, {
        name: controlName(p), label: t('polygons.fixedPoint'),
        get: () => s().fixedPoint !== null, set: (v) => (s().fixedPoint = v ? p.on : null),
      });
      c.range(polygons, {
        name: 'fixed-bits', label: t('polygons.fixedBits'), ...spanOf(p),
        get: () => s().fixedPoint ?? p.on, set: (v) => (s().fixedPoint = Math.round(v)),
        visible: () => s().fixedPoint !== null,
      });
      c.details(polygons, { summary: t('polygons.fixedPoint.explain'), text: () => lab('about.fixed_point') });
    },
    // The palette switched on and off, its shades and first entry shown while it is on; the entries end at 256.
    'palette.shades': (shades) => {
      const offset = param('palette.offset');
      c.checkbox(polygons, {
        name: 'palette', label: t('polygons.palette'),
        get: () => s().palette !== null,
        set: (v) => (s().palette = v ? { shades: shades.default, offset: offset.default } : null),
      });
      c.range(polygons, {
        name: controlName(shades), label: t('polygons.shades'), ...spanOf(shades),
        get: () => s().palette?.shades ?? shades.default,
        set: (v) => {
          const n = Math.round(v);
          s().palette = { shades: n, offset: Math.min(s().palette?.offset ?? 0, 256 - n) };
        },
        visible: () => s().palette !== null,
      });
      c.range(polygons, {
        name: controlName(offset), label: t('polygons.offset'), min: offset.min, step: offset.step,
        max: () => shades.max - (s().palette?.shades ?? shades.default),
        get: () => s().palette?.offset ?? offset.default,
        set: (v) => (s().palette = { shades: s().palette?.shades ?? shades.default, offset: Math.round(v) }),
        hint: () => t('polygons.offset.hint'),
        visible: () => s().palette !== null,
      });
      c.details(polygons, { summary: t('polygons.palette.explain'), text: () => lab('about.palette') });
    },
    'palette.offset': null,
    // 'tiled' cannot draw the modes above: the scanline rasterizer draws while one is on.
    rasterizer: (p) => {
      c.select(polygons, {
        name: 'rasterizer', label: t('shading.rasterizer'),
        options: () => options('shading.rasterizer', p.choices).map(([v, l]) => [v, l, v === 'tiled' && needsScanline(s())]),
        get: () => rasterizerOf(s()), set: (v) => (s().rasterizer = v),
      });
      c.note(polygons, () => (needsScanline(s()) ? t('polygons.scanlineOnly') : t('polygons.rasterizer.hint')));
    },
  });

  const view = c.group('group.view', 'view');
  params(view, 'view', {
    // The usual sizes, and the state's own when a link gave another.
    size: (p) => c.select(view, {
      name: 'size', label: t('view.size'),
      options: () => [...new Set([...p.choices, s().size])].sort((a, b) => a - b).map((n) => [String(n), `${n} × ${n}`]),
      get: () => String(s().size), set: (v) => (s().size = Number(v)),
    }),
  });
  // What "Save animation" saves: not part of the scene, so no frame is drawn again.
  params(view, 'animation');
  return c;
}
