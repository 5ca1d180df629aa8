// The column of controls beside the panels: every parameter of the scene the
// three panels render, group by group. Each control's range, step and
// default come from the table of parameters (params.js); this file says only
// which control shows which parameter, with its label (controls.js builds
// them). Built again when the language changes.
import { t, lab } from './i18n.js';
import { el } from './dom.js';
import { Controls } from './controls.js';
import { param, MAX_LIGHTS } from './params.js';
import {
  PRESETS, MAX_FILE_MIB, MESH_EXTENSIONS, presetOf, needsScanline, rasterizerOf, defaultLight, withKind,
} from './state.js';

/** A range control's span, step and accepted values, from the parameter's declaration. */
function spanOf(p) {
  const [min, max] = p.slider ?? [p.min, p.max];
  return { min, max, step: p.step, accept: [p.min, p.max] };
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

  const model = c.group('group.model', 'model');
  c.select(model, {
    name: 'model',
    label: t('model.source'),
    options: () => [
      ...page.models().map((m) => [m.name, modelName(m.name)]),
      ...(page.userFile() ? [[page.userFile().name, page.userFile().name]] : []),
    ],
    get: () => s().model,
    // Another model is framed: the camera starts again (the control's change re-renders).
    set: (v) => page.setModel(v, false),
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
  c.range(ambient, { name: 'ambient-intensity', label: t('ambient.intensity'), ...spanOf(param('ambient.intensity')), get: () => s().ambient.intensity, set: (v) => (s().ambient.intensity = v) });

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
      const head = el('div', { class: 'light-head' });
      block.append(head);
      head.append(el('span', { class: 'swatch light-swatch', 'aria-hidden': 'true' }));
      lc.onRefresh(() => head.firstChild.style.setProperty('background', lightSwatch(L())));
      head.firstChild.style.setProperty('background', lightSwatch(L()));
      lc.checkbox(head, { name: `light-${n}-on`, label: t('lights.on', { n }), get: () => L().on, set: (v) => (L().on = v) });
      const remove = el('button', { type: 'button', class: 'light-remove', text: t('lights.remove'), 'aria-label': t('lights.remove.label', { n }) });
      remove.addEventListener('click', () => {
        s().lights.splice(k, 1);
        page.changed();
      });
      head.append(remove);
      lc.select(block, {
        name: `light-${n}-kind`, label: t('lights.kind'),
        options: () => options('lights.kind', param('kind', 'light').choices),
        get: () => L().kind,
        set: (v) => (s().lights[k] = withKind(L(), v)),
      });
      lc.rgb(block, { name: `light-${n}-color`, label: t('light.color'), get: () => L().color, set: (v) => (L().color = v) });
      lc.range(block, { name: `light-${n}-intensity`, label: t('light.intensity'), ...spanOf(param('intensity', 'light')), get: () => L().intensity, set: (v) => (L().intensity = v) });
      const vector = L().kind === 'point' ? 'position' : 'direction';
      for (const [axis, i] of [['x', 0], ['y', 1], ['z', 2]]) {
        lc.range(block, {
          name: `light-${n}-${axis}`, label: t(`light.${vector}.${axis}`), ...spanOf(param(vector, 'light')),
          get: () => L()[vector][i],
          set: (v) => {
            const p = [...L()[vector]];
            p[i] = v;
            // A direction of zero has no meaning: keep the last that had one.
            if (vector === 'direction' && p.every((x) => x === 0)) return;
            L()[vector] = p;
          },
        });
      }
      // A point light's fall-off with distance: k0 + k1·d + k2·d² divides its light.
      if (L().kind === 'point') {
        for (const [term, i] of [['constant', 0], ['linear', 1], ['quadratic', 2]]) {
          lc.range(block, {
            name: `light-${n}-attenuation-${term}`, label: t(`light.attenuation.${term}`), ...spanOf(param('attenuation', 'light')),
            get: () => L().attenuation[i],
            set: (v) => {
              const k = [...L().attenuation];
              k[i] = v;
              L().attenuation = k;
            },
          });
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
  for (const k of ['ka', 'kd', 'ks']) {
    c.rgb(material, { name: k, label: t(`material.${k}`), get: () => s().material[k], set: (v) => (s().material[k] = v) });
  }
  c.range(material, { name: 'shininess', label: t('material.shininess'), ...spanOf(param('material.shininess')), get: () => s().material.shininess, set: (v) => (s().material.shininess = v) });

  const camera = c.group('group.camera', 'camera');
  const yaw = param('camera.yaw');
  const half = yaw.wrap / 2;
  c.range(camera, { name: 'yaw', label: t('camera.yaw'), ...spanOf(yaw), accept: yaw.slider, get: () => ((((s().camera.yaw + half) % yaw.wrap) + yaw.wrap) % yaw.wrap) - half, set: (v) => (s().camera.yaw = v) });
  c.range(camera, { name: 'pitch', label: t('camera.pitch'), ...spanOf(param('camera.pitch')), get: () => s().camera.pitch, set: (v) => (s().camera.pitch = v) });
  c.range(camera, { name: 'zoom', label: t('camera.zoom'), ...spanOf(param('camera.zoom')), get: () => s().camera.zoom, set: (v) => (s().camera.zoom = v) });
  c.select(camera, {
    name: 'drag', label: t('camera.drag'), options: () => options('camera.drag', ['camera', 'light']),
    get: () => page.dragMode(), set: (v) => page.setDragMode(v),
  });
  c.button(camera, { label: t('camera.reset'), onclick: page.resetCamera });
  c.note(camera, () => t('camera.help'));

  const shading = c.group('group.shading', 'shading');
  c.select(shading, {
    name: 'normals', label: t('shading.normals'),
    options: () => options('shading.normals', param('normals').choices).map(([v, l]) => {
      const file = page.userFile();
      return [v, l, v === 'file' && !(file && s().model === file.name && file.has_normals)];
    }),
    get: () => s().normals, set: (v) => (s().normals = v),
  });
  c.range(shading, {
    name: 'crease', label: t('shading.crease'), ...spanOf(param('crease')),
    get: () => s().crease ?? page.modelInfo()?.default_crease ?? 180, set: (v) => (s().crease = v),
    hint: () => t('shading.crease.hint'),
  });
  c.checkbox(shading, { name: 'gouraud-specular', label: t('shading.gouraudSpecular'), get: () => s().gouraudSpecular, set: (v) => (s().gouraudSpecular = v) });
  c.select(shading, { name: 'interpolation', label: t('shading.interpolation'), options: () => options('shading.interpolation', param('interpolation').choices), get: () => s().interpolation, set: (v) => (s().interpolation = v) });
  c.details(shading, { summary: t('explain.summary'), text: () => lab(`about.interpolation_${s().interpolation}`) });
  c.checkbox(shading, { name: 'cull', label: t('shading.cull'), get: () => s().cull, set: (v) => (s().cull = v) });
  c.select(shading, { name: 'specular', label: t('shading.specular'), options: () => options('shading.specular', param('specular').choices), get: () => s().specular, set: (v) => (s().specular = v) });
  c.note(shading, () => t(`shading.specular.${s().specular}.hint`));
  c.details(shading, { summary: t('shading.specular.explain'), text: () => lab('about.blinn') });

  // Interpolation on polygons, and the modes of old hardware: all drawn by the scanline rasterizer.
  const polygons = c.group('group.polygons', 'polygons');
  c.select(polygons, { name: 'polygons', label: t('shading.polygons'), options: () => options('shading.polygons', param('polygons').choices), get: () => s().polygons, set: (v) => (s().polygons = v) });
  c.details(polygons, { summary: t('explain.summary'), text: () => lab(`about.polygons_${s().polygons}`) });
  c.checkbox(polygons, {
    name: 'fixed-point', label: t('polygons.fixedPoint'),
    get: () => s().fixedPoint !== null, set: (v) => (s().fixedPoint = v ? param('fixedPoint').on : null),
  });
  c.range(polygons, {
    name: 'fixed-bits', label: t('polygons.fixedBits'), ...spanOf(param('fixedPoint')),
    get: () => s().fixedPoint ?? param('fixedPoint').on, set: (v) => (s().fixedPoint = Math.round(v)),
    visible: () => s().fixedPoint !== null,
  });
  c.details(polygons, { summary: t('polygons.fixedPoint.explain'), text: () => lab('about.fixed_point') });
  c.checkbox(polygons, {
    name: 'palette', label: t('polygons.palette'),
    get: () => s().palette !== null,
    set: (v) => (s().palette = v ? { shades: param('palette.shades').default, offset: param('palette.offset').default } : null),
  });
  c.range(polygons, {
    name: 'palette-shades', label: t('polygons.shades'), ...spanOf(param('palette.shades')),
    get: () => s().palette?.shades ?? param('palette.shades').default,
    set: (v) => {
      const shades = Math.round(v);
      s().palette = { shades, offset: Math.min(s().palette?.offset ?? 0, 256 - shades) };
    },
    visible: () => s().palette !== null,
  });
  c.range(polygons, {
    name: 'palette-offset', label: t('polygons.offset'), min: param('palette.offset').min, step: param('palette.offset').step,
    max: () => param('palette.shades').max - (s().palette?.shades ?? param('palette.shades').default),
    get: () => s().palette?.offset ?? param('palette.offset').default,
    set: (v) => (s().palette = { shades: s().palette?.shades ?? param('palette.shades').default, offset: Math.round(v) }),
    hint: () => t('polygons.offset.hint'),
    visible: () => s().palette !== null,
  });
  c.details(polygons, { summary: t('polygons.palette.explain'), text: () => lab('about.palette') });
  c.select(polygons, {
    name: 'rasterizer', label: t('shading.rasterizer'),
    options: () => options('shading.rasterizer', param('rasterizer').choices).map(([v, l]) => [v, l, v === 'tiled' && needsScanline(s())]),
    get: () => rasterizerOf(s()), set: (v) => (s().rasterizer = v),
  });
  c.note(polygons, () => (needsScanline(s()) ? t('polygons.scanlineOnly') : t('polygons.rasterizer.hint')));

  const view = c.group('group.view', 'view');
  c.select(view, {
    name: 'size', label: t('view.size'),
    options: () => [...new Set([...param('size').choices, s().size])].sort((a, b) => a - b).map((n) => [String(n), `${n} × ${n}`]),
    get: () => String(s().size), set: (v) => (s().size = Number(v)),
  });
  c.rgb(view, { name: 'background', label: t('view.background'), get: () => s().background, set: (v) => (s().background = v) });
  // What "Save animation" saves: not part of the scene, so no frame is drawn again.
  for (const [key, name] of [['frames', 'view.animation.frames'], ['delay', 'view.animation.delay']]) {
    c.range(view, { name: `animation-${key}`, label: t(name), ...spanOf(param(`animation.${key}`)), get: () => s().animation[key], set: (v) => (s().animation[key] = Math.round(v)) });
  }
  return c;
}
