// The scene's parameters on the page, end to end in headless Chromium:
// every parameter of the core's table has a labelled control in each
// language; a light's attenuation acts on all three panels and travels
// through the link and the scene file; a link with a bad value is refused
// with a message; a link with the whole state reproduces the view.
//
// Run with the other browser tests: (cd tests/browser && npm ci && npm test)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import {
  useViewer, ARTIFACTS, METHODS, openViewer, settle, update, digests, panelPixels,
} from './harness.js';

useViewer();

test("a point light's attenuation dims all three panels, from its slider to the link and the scene file", async () => {
  const { page, problems } = await openViewer();
  const mean = async (m) => {
    const rgba = Buffer.from(await panelPixels(page, m), 'base64');
    let sum = 0;
    for (let i = 0; i < rgba.length; i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
    return sum / (rgba.length / 4);
  };
  const before = {};
  for (const m of METHODS) before[m] = await mean(m);
  // The light is about 4 units from the teapot: k2 = 0.1 divides its light by about 2.6.
  const quadratic = page.getByLabel('Fall-off: quadratic', { exact: true });
  await quadratic.focus();
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.lights[0].attenuation), [1, 0, 0.1]);
  for (const m of METHODS) {
    const after = await mean(m);
    assert.ok(after < before[m] * 0.85, `${m}: ${after} is darker than ${before[m]}`);
  }
  assert.match(await page.evaluate(() => window.shadelab.sceneToml('phong')), /\[\[lights\]\]\n(?:.*\n)*?attenuation = \[1(?:\.0)?, 0(?:\.0)?, 0\.1\]\n/);
  await page.waitForFunction(() => location.hash.includes('lightAtt='));
  const hash = await page.evaluate(() => location.hash);
  const pictures = await digests(page);
  const second = await openViewer(hash);
  assert.deepEqual(await second.page.evaluate(() => window.shadelab.state.lights[0].attenuation), [1, 0, 0.1]);
  assert.deepEqual(await digests(second.page), pictures);
  // With two lights the link lists each one, its attenuation included.
  await update(page, 's.lights.push({ ...s.lights[0], position: [-2, 1, 2], attenuation: [0.5, 0.2, 0] })');
  await page.waitForFunction(() => location.hash.includes('lights='));
  const third = await openViewer(await page.evaluate(() => location.hash));
  assert.deepEqual(
    await third.page.evaluate(() => window.shadelab.state.lights.map((l) => l.attenuation)),
    [[1, 0, 0.1], [0.5, 0.2, 0]],
  );
  assert.deepEqual([...problems, ...second.problems, ...third.problems], []);
  await Promise.all([page.close(), second.page.close(), third.page.close()]);
});

test('a link with a negative fall-off term is refused: the light keeps its default and the page says so', async () => {
  for (const [hash, key] of [
    ['#lightAtt=1,-0.5,0', 'lightAtt'],
    ['#lights=point:2,2,3:255,255,255:1:1,0,-0.1;directional:0,0,-1:255,255,255:1', 'lights'],
  ]) {
    const { page, problems } = await openViewer(hash);
    await page.locator('#message').waitFor({ state: 'visible' });
    assert.equal(await page.locator('#message .message-text').textContent(), `The link’s value for “${key}” is not valid and was ignored.`);
    assert.deepEqual(await page.evaluate(() => window.shadelab.state.lights.map((l) => [l.kind, l.attenuation])), [['point', [1, 0, 0]]]);
    assert.match(await page.evaluate(() => window.shadelab.sceneToml()), /\nattenuation = \[1\.0, 0\.0, 0\.0\]\n/);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('a point light with a fall-off and a directional light: the scene file and the link are exactly these, and the link reads back', async () => {
  const { page, problems } = await openViewer();
  // The directional light keeps an attenuation from when it was a point light: neither file nor link has it.
  await update(page, `s.lights = [
    { ...s.lights[0], position: [1.5, -2, 3.25], color: [255, 200, 100], intensity: 0.8, attenuation: [1, 0.05, 0.01] },
    { ...s.lights[0], kind: 'directional', direction: [-0.5, -1, -0.25], color: [100, 150, 255], intensity: 0.6, attenuation: [0.5, 0, 0] },
  ]`);
  assert.equal(await page.evaluate(() => window.shadelab.sceneToml()), [
    '[model]', 'source = "teapot"', 'normals = "auto"', '',
    '[ambient]', 'color = [255, 255, 255]', 'intensity = 0.2', '',
    '[[lights]]', 'kind = "point"', 'position = [1.5, -2.0, 3.25]', 'color = [255, 200, 100]', 'intensity = 0.8', 'attenuation = [1.0, 0.05, 0.01]', '',
    '[[lights]]', 'kind = "directional"', 'direction = [-0.5, -1.0, -0.25]', 'color = [100, 150, 255]', 'intensity = 0.6', '',
    '[material]', 'ka = [200, 60, 60]', 'kd = [200, 60, 60]', 'ks = [255, 255, 255]', 'shininess = 32.0', '',
    '[render]', 'width = 480', 'height = 480', 'background = [0, 0, 0]', 'cull_backfaces = true', 'gouraud_specular = false',
    'interpolation = "perspective"', 'rasterizer = "tiled"', 'polygons = "fans"', 'specular = "phong"', 'yaw = 0.0', 'pitch = 0.0', 'zoom = 1.0', '',
  ].join('\n'));
  // lights=point:1.5,-2,3.25:255,200,100:0.8:1,0.05,0.01;directional:-0.5,-1,-0.25:100,150,255:0.6
  const link = '#lights=point%3A1.5%2C-2%2C3.25%3A255%2C200%2C100%3A0.8%3A1%2C0.05%2C0.01%3Bdirectional%3A-0.5%2C-1%2C-0.25%3A100%2C150%2C255%3A0.6';
  await page.waitForFunction((h) => location.hash === h, link);
  // Off, the directional light says so last.
  await update(page, 's.lights[1].on = false');
  await page.waitForFunction((h) => location.hash === `${h}%3Aoff`, link);
  const lights = (l) => l.map(({ on, kind, position, direction, color, intensity, attenuation }) => ({ on, kind, ...(kind === 'point' ? { position, attenuation } : { direction }), color, intensity }));
  const expected = lights(await page.evaluate(() => window.shadelab.state.lights));
  const second = await openViewer(await page.evaluate(() => location.hash));
  assert.deepEqual(lights(await second.page.evaluate(() => window.shadelab.state.lights)), expected);
  assert.deepEqual([...problems, ...second.problems], []);
  await Promise.all([page.close(), second.page.close()]);
  // The links made before: four fields (no attenuation), five with :off, one point light's own keys.
  for (const [hash, want] of [
    ['#lights=point:2,2,3:255,255,255:1;directional:0,0,-1:10,20,30:0.5:off', [['point', [1, 0, 0], true], ['directional', [1, 0, 0], false]]],
    ['#lightPos=1,2,3&lightAtt=1,0,0.1', [['point', [1, 0, 0.1], true]]],
  ]) {
    const old = await openViewer(hash);
    assert.deepEqual(await old.page.evaluate(() => window.shadelab.state.lights.map((l) => [l.kind, l.attenuation, l.on])), want, hash);
    assert.deepEqual(old.problems, []);
    await old.page.close();
  }
});

test('every parameter of the table has a labelled control in each language, and each light parameter its line in a light it applies to', async () => {
  const { page, problems } = await openViewer();
  // Every control on show: a point and a directional light, fixed point and a palette.
  await update(page, `s.lights.push({ ...s.lights[0], kind: 'directional', direction: [-1, -0.5, -1] }); s.fixedPoint = 8; s.palette = { shades: 8, offset: 0 };`);
  /** In the page: what is wrong with the controls of the table's parameters and with the lights' lines. */
  const audit = () => page.evaluate(async () => {
    const { PARAMS, applies } = await import('./js/params.js');
    const { controlNames } = await import('./js/form.js');
    const { state } = window.shadelab;
    const wrong = [];
    let labels = 0;
    const labelled = (p, names) => {
      for (const name of names) {
        const row = document.querySelector(`#controls [data-control="${name}"]`);
        const label = row && !row.closest('[hidden]') ? row.querySelector('label')?.textContent.trim() : undefined;
        // A raw key is what the string tables give for a key they lack.
        if (!label || /^[\w-]+(\.[\w-]+)+$/.test(label)) wrong.push(`${p.key}: ${name}: ${label}`);
        else labels += 1;
      }
    };
    const blocks = window.shadelab.sceneToml().split('[[lights]]\n').slice(1).map((b) => b.split('\n\n')[0].split('\n'));
    for (const p of PARAMS.filter((q) => q.key)) {
      if (p.group !== 'light') {
        labelled(p, controlNames(p));
        continue;
      }
      state.lights.forEach((light, k) => {
        const names = controlNames(p, `light-${k + 1}`);
        // A point light's position and a directional light's direction share their sliders' names (light-1-x).
        const others = PARAMS.filter((q) => q.group === 'light' && q.key && applies(q, light)).flatMap((q) => controlNames(q, `light-${k + 1}`));
        const line = blocks[k].some((l) => l.startsWith(`${p.key.split('.').pop()} = `));
        if (applies(p, light)) {
          labelled(p, names);
          if (!line) wrong.push(`${p.key}: no line in light ${k + 1}'s [[lights]]`);
        } else {
          if (names.some((n) => !others.includes(n) && document.querySelector(`#controls [data-control="${n}"]`))) wrong.push(`${p.key}: a control in light ${k + 1}, which has none`);
          if (line) wrong.push(`${p.key}: a line in light ${k + 1}'s [[lights]], which has none`);
        }
      });
    }
    return { wrong, labels };
  });
  const counts = [];
  for (const lang of ['en', 'ru', 'sk', 'cs']) {
    await page.selectOption('#language', lang);
    await settle(page);
    const { wrong, labels } = await audit();
    assert.deepEqual(wrong, [], lang);
    counts.push(labels);
  }
  // The model, its detail and crease, the ambient light, a point and a directional light (8 + 5), the material,
  // the camera, the shading and polygon options, the background: 35 today.
  assert.deepEqual(counts, Array(4).fill(counts[0]));
  assert.ok(counts[0] >= 35, `${counts[0]} labelled controls`);
  // A parameter no table names is labelled by the core's table, in English; every param.* key of the tables names a parameter.
  const found = await page.evaluate(async () => {
    const { PARAMS } = await import('./js/params.js');
    const { labelOf, optionLabel } = await import('./js/form.js');
    const made = { name: 'spread', key: 'lights.spread', group: 'light', kind: 'vec3', label: 'Spread', parts: ['near', 'mid', 'far'] };
    const fallback = [labelOf(made), labelOf(made, 'mid'), optionLabel(made, 'wide')];
    const names = new Set(PARAMS.flatMap((p) => {
      const key = `param.${p.key ?? p.name}`;
      return [key, ...(p.parts ?? []).map((part) => `${key}.${part}`), ...(p.kind === 'choice' ? p.choices.map((c) => `${key}.${c}`) : [])];
    }));
    const stale = [];
    for (const lang of ['en', 'ru', 'sk', 'cs']) {
      const table = (await import(`./i18n/${lang}.js`)).default;
      stale.push(...Object.keys(table).filter((k) => k.startsWith('param.') && !names.has(k)).map((k) => `${lang}: ${k}`));
    }
    return { fallback, stale };
  });
  assert.deepEqual(found.fallback, ['Spread', 'Spread: mid', 'wide']);
  assert.deepEqual(found.stale, []);
  assert.deepEqual(problems, []);
  await page.close();
});

test('a link with the state reproduces the view', async () => {
  const { page, problems } = await openViewer();
  await update(page, `
    s.model = 'torus'; s.detail = 10; s.normals = 'area'; s.crease = 45;
    s.ambient.color = [200, 220, 255]; s.ambient.intensity = 0.35;
    s.lights[0].color = [255, 240, 200]; s.lights[0].intensity = 1.4; s.lights[0].position = [-2, 3, 1.5];
    s.material = { ka: [20, 80, 200], kd: [20, 80, 200], ks: [255, 255, 255], shininess: 80 };
    s.camera = { yaw: 35, pitch: -20, zoom: 1.3 };
    s.gouraudSpecular = true; s.interpolation = 'screen'; s.cull = false; s.specular = 'blinn-phong';
    s.size = 400; s.background = [10, 20, 30];`);
  await page.waitForFunction(() => location.hash.includes('torus') && location.hash.includes('size=400'));
  const hash = await page.evaluate(() => location.hash);
  const state = await page.evaluate(() => window.shadelab.state);
  const pictures = await digests(page);
  const second = await openViewer(hash);
  assert.deepEqual(await second.page.evaluate(() => window.shadelab.state), state);
  assert.deepEqual(await digests(second.page), pictures);
  await second.page.screenshot({ path: path.join(ARTIFACTS, 'from-link.png') });
  assert.deepEqual([...problems, ...second.problems], []);

  // A link naming the user's file, or with nonsense, says so and shows the rest.
  const third = await openViewer('#model=mine.obj&shininess=banana&yaw=20');
  const message = await third.page.locator('#message .message-text').textContent();
  assert.match(message, /mine\.obj/);
  assert.match(message, /shininess/);
  assert.equal(await third.page.evaluate(() => window.shadelab.state.camera.yaw), 20);
  await Promise.all([page.close(), second.page.close(), third.page.close()]);
});
