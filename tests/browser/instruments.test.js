// The teaching instruments in the real page: clicking a pixel inspects it
// with the numbers `shadelab explain` prints, choosing a row plots what the
// panels show, the error maps are those of `shadelab errors`, overlays are
// those of `shadelab render --overlay`, the old hardware's modes draw what
// they should, and every label speaks the chosen language. Screenshots of
// each instrument go to ./artifacts/.
//
// Run with the other browser tests: (cd tests/browser && npm ci && npm test)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  useViewer, context, baseUrl, ROOT, ARTIFACTS, METHODS,
  openViewer, settle, quiet, update, digests, statistics, decodePng, shadelab, pixelsOf,
} from './harness.js';

useViewer();

const TMP = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-instruments-'));


/**
 * A screenshot of the page: the panels and, under them, the open
 * instrument scrolled to `part` (a selector in it), 1600 × 1000 pixels, as
 * the README shows them (docs/images/viewer-*.png are copies).
 */
async function shot(page, name, part) {
  await page.evaluate((sel) => {
    window.scrollTo(0, 0);
    const tool = document.querySelector('#side .tool:not([hidden])');
    const target = sel && tool?.querySelector(sel);
    if (target) {
      const side = document.querySelector('#side');
      const tabs = side.querySelector('.tabs');
      side.scrollTop += target.getBoundingClientRect().top - side.getBoundingClientRect().top - tabs.offsetHeight - 4;
    }
  }, part);
  await page.screenshot({ path: path.join(ARTIFACTS, name) });
}

/** Clicks pixel (x, y) of a panel, as a user does, holding `modifiers`. */
async function clickPixel(page, method, x, y, modifiers = []) {
  const canvas = page.locator(`.panel[data-method="${method}"] canvas`);
  const box = await canvas.boundingBox();
  const size = await canvas.evaluate((c) => [c.width, c.height]);
  for (const m of modifiers) await page.keyboard.down(m);
  await page.mouse.click(box.x + ((x + 0.5) * box.width) / size[0], box.y + ((y + 0.5) * box.height) / size[1]);
  for (const m of modifiers) await page.keyboard.up(m);
  await quiet(page);
}

/** The page's scene for `shadelab compare` (all three methods), written to a file. */
async function sceneFile(page, name, method) {
  const file = path.join(TMP, name);
  fs.writeFileSync(file, await page.evaluate((m) => window.shadelab.sceneToml(m), method));
  return file;
}


test('clicking a pixel inspects it with the numbers `shadelab explain` prints', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=8&interpolation=screen&polygons=whole');
  await clickPixel(page, 'gouraud', 290, 190);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.pixel), [290, 190]);
  assert.equal(await page.evaluate(() => window.shadelab.view.tab), 'inspector');
  const scene = await sceneFile(page, 'inspect.toml');
  let inspection = await page.evaluate(() => window.shadelab.inspection);
  assert.equal(inspection.text, shadelab('explain', scene, '--pixel', '290,190'));
  // The page shows every line of it, and marks P, Q and the polygon on each panel.
  const shown = await page.locator('#tool-inspector').innerText();
  for (const line of inspection.text.split('\n')) {
    const text = line.trim().replace(/^== /, '');
    if (text) assert.ok(shown.replace(/\s+/g, ' ').includes(text.replace(/\s+/g, ' ')), `the page shows: ${text}`);
  }
  assert.match(inspection.text, /I_O = \(1 − u\)·I_P \+ u·I_Q = /);
  for (const m of METHODS) {
    const marks = page.locator(`.panel[data-method="${m}"] svg.marks`);
    assert.equal(await marks.locator('.mark-point').count(), 2, `${m}: P and Q`);
    assert.equal(await marks.locator('.mark-polygon').count(), 1, `${m}: the polygon walked`);
    assert.ok(await marks.locator('rect.mark-pixel').count() >= 1, `${m}: the pixel`);
  }
  // The colour it names is the panel's pixel (the scanline rasterizer draws these: exactly).
  for (const m of inspection.methods) {
    const px = await pixelsOf(page, m.method);
    const k = (190 * 480 + 290) * 4;
    assert.deepEqual([px[k], px[k + 1], px[k + 2]], m.color, m.method);
  }
  await shot(page, 'inspector.png', '.inspect-methods');

  // Drawn by the tiled rasterizer, it says it explains the scanline reference,
  // and its colours are the panel's within 1/255; in fixed point it says so too.
  await update(page, "s.polygons = 'fans'; s.rasterizer = 'tiled'; s.pixel = [200, 260]");
  await quiet(page);
  inspection = await page.evaluate(() => window.shadelab.inspection);
  assert.match(inspection.header, /Traced on the scanline reference rasterizer; .* agree within 1\/255/);
  assert.equal(inspection.text, shadelab('explain', await sceneFile(page, 'inspect-tiled.toml'), '--pixel', '200,260'));
  for (const m of inspection.methods) {
    const px = await pixelsOf(page, m.method);
    const k = (260 * 480 + 200) * 4;
    for (let c = 0; c < 3; c++) assert.ok(Math.abs(px[k + c] - m.color[c]) <= 1, `${m.method}: ${px[k + c]} vs ${m.color[c]}`);
  }
  await update(page, 's.fixedPoint = 6');
  await quiet(page);
  inspection = await page.evaluate(() => window.shadelab.inspection);
  assert.match(inspection.header, /fixed point with 6 fraction bits/);
  assert.equal(inspection.text, shadelab('explain', await sceneFile(page, 'inspect-fixed.toml'), '--pixel', '200,260'));

  // In another language, the same numbers in the words of `--lang`.
  await page.selectOption('#language', 'cs');
  await quiet(page);
  inspection = await page.evaluate(() => window.shadelab.inspection);
  assert.equal(inspection.text, shadelab('explain', await sceneFile(page, 'inspect-cs.toml'), '--pixel', '200,260', '--lang', 'cs'));
  assert.match(inspection.text, /^== Gouraudovo stínování$/m);
  // A background pixel says so.
  await update(page, 's.pixel = [2, 2]');
  await quiet(page);
  assert.match(await page.locator('#tool-inspector').innerText(), /Tento pixel nepokrývá žádný polygon/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('choosing a row plots the intensity the panels show, with its derivative and the edges', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=10&interpolation=screen');
  await clickPixel(page, 'phong', 120, 230, ['Alt']);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.profile), { row: 230 });
  assert.equal(await page.evaluate(() => window.shadelab.view.tab), 'profile');
  const profile = await page.evaluate(() => window.shadelab.profile);
  assert.deepEqual(profile.curves.map((c) => c.kind), ['flat', 'gouraud', 'phong', 'exact']);
  assert.equal(profile.pixels.length, 480);
  for (const curve of profile.curves.slice(0, 3)) {
    const px = await pixelsOf(page, curve.kind);
    let drawn = 0;
    for (let x = 0; x < 480; x++) {
      const k = (230 * 480 + x) * 4;
      const background = px[k] === 0 && px[k + 1] === 0 && px[k + 2] === 0;
      const v = curve.values[x];
      assert.equal(v === null, background, `${curve.kind} x=${x}: drawn where the panel is`);
      if (v === null) continue;
      drawn += 1;
      // The curve is the light before rounding; the tiled panel rounds it, within 1/255 of the reference.
      const shown = (px[k] + px[k + 1] + px[k + 2]) / 3;
      assert.ok(Math.abs(shown - v) <= 1.5, `${curve.kind} x=${x}: panel ${shown}, curve ${v}`);
      if (x > 0 && curve.values[x - 1] !== null) assert.ok(Math.abs(curve.derivative[x - 1] - (v - curve.values[x - 1])) < 1e-9);
    }
    assert.ok(drawn > 200, `${curve.kind}: ${drawn} samples`);
  }
  // Flat is constant on each polygon; Gouraud's slope is constant on each piece; the edges are marked.
  const [flat, gouraud] = profile.curves;
  const edges = new Set(flat.edges);
  for (let k = 0; k + 1 < 480; k++) {
    if (flat.values[k] !== null && flat.values[k + 1] !== null && !edges.has(k)) assert.ok(Math.abs(flat.values[k + 1] - flat.values[k]) < 1e-3, `flat at ${k}`);
  }
  assert.ok(gouraud.polygon_edges.length >= 2, JSON.stringify(gouraud.polygon_edges));
  // Drawn: the plots are not blank, the row is marked on every panel.
  for (const selector of ['.plot-intensity', '.plot-derivative']) {
    const inked = await page.locator(selector).evaluate((c) => {
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 3; i < d.length; i += 4) n += d[i] > 0;
      return n;
    });
    assert.ok(inked > 1000, `${selector}: ${inked} pixels drawn`);
  }
  for (const m of METHODS) assert.equal(await page.locator(`.panel[data-method="${m}"] svg .mark-profile`).count(), 2);
  await page.locator('.plot-intensity').hover({ position: { x: 200, y: 100 } });
  assert.match(await page.locator('#tool-profile .readout').innerText(), /^Pixel \(\d+, 230\): Flat [\d.]+ · Gouraud/);
  await shot(page, 'profile.png', '.legend');

  // Alt+drag draws a line to plot along.
  const box = await page.locator('.panel[data-method="gouraud"] canvas').boundingBox();
  await page.keyboard.down('Alt');
  await page.mouse.move(box.x + box.width * 0.2, box.y + box.height * 0.8);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(box.x + box.width * (0.2 + 0.06 * i), box.y + box.height * (0.8 - 0.06 * i));
  await page.mouse.up();
  await page.keyboard.up('Alt');
  await quiet(page);
  const line = await page.evaluate(() => window.shadelab.state.profile.line);
  assert.ok(Math.abs(line[0] - 96) < 2 && Math.abs(line[1] - 384) < 2 && Math.abs(line[2] - 384) < 2 && Math.abs(line[3] - 96) < 2, JSON.stringify(line));
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), 0, 'Alt+drag does not orbit');
  const along = await page.evaluate(() => window.shadelab.profile);
  assert.ok(along.pixels.length >= 288 && along.pixels.length <= 290, `${along.pixels.length} samples`);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the error maps of a sphere are those `shadelab errors` computes and prints', async () => {
  const { page, problems } = await openViewer('#model=sphere&rasterizer=scanline&tab=errors');
  await page.getByLabel('Show the error maps in the panels').check();
  await quiet(page);
  assert.ok(await page.locator('.panel[data-method="exact"]').isVisible(), 'the exact surface is the fourth panel');
  const scene = await sceneFile(page, 'errors.toml');
  const png = path.join(TMP, 'errors.png');
  const out = shadelab('errors', scene, '-o', png);
  const printed = Object.fromEntries(out.split('\n').map((l) => l.match(/^(Flat|Gouraud|Phong)\s+([\d.]+)\s+([\d.]+)/)).filter(Boolean).map((m) => [m[1].toLowerCase(), { mean: m[2], max: m[3] }]));
  const scale = Number(out.match(/colour scale 0–([\d.]+)/)[1]);
  const frames = await page.evaluate(() => Object.fromEntries(window.shadelab.panels.map((p) => [p.method, p.last.errors])));
  for (const m of METHODS) {
    assert.equal(frames[m].mean.toFixed(3), printed[m].mean, `${m} mean`);
    assert.equal(frames[m].max.toFixed(2), printed[m].max, `${m} max`);
    assert.equal(frames[m].scale, scale, `${m} scale`);
    const row = page.locator(`#tool-errors tr[data-method="${m}"]`);
    assert.equal(await row.locator('.mean').innerText(), printed[m].mean);
    assert.equal(await row.locator('.max').innerText(), printed[m].max);
    assert.match(await page.locator(`.panel[data-method="${m}"] .stats`).innerText(), new RegExp(`mean ${Number(printed[m].mean).toFixed(2)}`));
  }
  // The heat maps and the exact surface are the sheet's panels, pixel for pixel.
  const sheet = await decodePng(page, png);
  const sheetPixels = Buffer.from(sheet.rgba, 'base64');
  const readCanvas = (selector) => page.locator(selector).evaluate((c) => [...c.getContext('2d').getImageData(0, 0, c.width, c.height).data]);
  const panelsInSheet = [['exact', '.panel[data-method="exact"] canvas'], ...METHODS.map((m) => [m, `.panel[data-method="${m}"] canvas`])];
  for (const [k, [name, selector]] of panelsInSheet.entries()) {
    const shown = await readCanvas(selector);
    let differing = 0;
    for (let y = 0; y < 480; y++) {
      for (let x = 0; x < 480; x++) {
        const a = ((34 + y) * sheet.width + k * (480 + 6) + x) * 4;
        const b = (y * 480 + x) * 4;
        if (sheetPixels[a] !== shown[b] || sheetPixels[a + 1] !== shown[b + 1] || sheetPixels[a + 2] !== shown[b + 2]) differing += 1;
      }
    }
    assert.equal(differing, 0, `${name}: the page's picture is the sheet's`);
  }
  await shot(page, 'errors.png', '.scale');
  // The worst pixel, one click away.
  await page.locator('#tool-errors tr[data-method="gouraud"] button.link').click();
  await quiet(page);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.pixel), frames.gouraud.max_at);
  // A fixed scale colours all three alike.
  await page.evaluate(() => window.shadelab.setTab('errors'));
  await page.getByLabel('Colour scale').selectOption('50');
  await quiet(page);
  assert.deepEqual(await page.evaluate(() => window.shadelab.panels.map((p) => p.last.errors.scale)), [50, 50, 50]);
  // The teapot has no exact surface: the switch is off and says why.
  await update(page, "s.model = 'teapot'");
  await quiet(page);
  assert.ok(await page.locator('.panel[data-method="exact"]').isHidden());
  assert.ok(await page.getByLabel('Show the error maps in the panels').isDisabled());
  assert.match(await page.locator('#tool-errors .note').innerText(), /known only for the built-in sphere, torus, cylinder, cone/);
  assert.ok((await page.evaluate(() => window.shadelab.panels.every((p) => !p.last.errors))), 'the panels show the shading again');
  assert.deepEqual(problems, []);
  await page.close();
});

const OVERLAY_COLORS = { wireframe: [255, 230, 90], 'face-normals': [80, 220, 255], 'vertex-normals': [120, 255, 120], light: [255, 255, 255] };

test('each overlay draws on the panels what `shadelab render --overlay` draws', async () => {
  const { page, problems } = await openViewer('#model=torus&detail=12&pitch=30&rasterizer=scanline&tab=overlays');
  const plain = await digests(page);
  for (const name of Object.keys(OVERLAY_COLORS)) {
    await page.locator(`input[data-overlay="${name}"][data-panel="all"]`).check();
    await quiet(page);
    const now = await digests(page);
    for (const m of METHODS) {
      assert.notEqual(now[m], plain[m], `${name} changed the ${m} panel`);
      const png = path.join(TMP, `${m}-${name}.png`);
      shadelab('render', await sceneFile(page, `${m}.toml`, m), '--overlay', name, '-o', png);
      const cli = Buffer.from((await decodePng(page, png)).rgba, 'base64');
      const shown = await pixelsOf(page, m);
      let differing = 0;
      let colored = 0;
      const c = OVERLAY_COLORS[name];
      for (let i = 0; i < shown.length; i += 4) {
        if (shown[i] !== cli[i] || shown[i + 1] !== cli[i + 1] || shown[i + 2] !== cli[i + 2]) differing += 1;
        if (shown[i] === c[0] && shown[i + 1] === c[1] && shown[i + 2] === c[2]) colored += 1;
      }
      assert.equal(differing, 0, `${m} with ${name}: the page's pixels are the command line's`);
      assert.ok(colored > 10, `${m}: ${colored} pixels in the colour of ${name}`);
    }
    if (name === 'vertex-normals') await shot(page, 'overlays.png', 'table');
    await page.locator(`input[data-overlay="${name}"][data-panel="all"]`).uncheck();
    await quiet(page);
    assert.deepEqual(await digests(page), plain, `${name} off: the pictures are back`);
  }
  // One panel alone.
  await page.locator('input[data-overlay="wireframe"][data-panel="gouraud"]').check();
  await quiet(page);
  const one = await digests(page);
  assert.equal(one.flat, plain.flat);
  assert.notEqual(one.gouraud, plain.gouraud);
  assert.equal(one.phong, plain.phong);
  assert.ok(await page.locator('input[data-overlay="wireframe"][data-panel="all"]').evaluate((b) => b.indeterminate));
  assert.match(await page.evaluate(() => location.hash), /overlays\.gouraud=wireframe/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('an indexed palette of N shades draws exactly N shades, on the scanline rasterizer', async () => {
  // No ambient light and a light from the side: intensities from 0 to past 1, all shades used;
  // a background apart from the palette's black.
  const { page, problems } = await openViewer('#model=sphere&detail=24&ambientI=0&lightPos=4,1,1.5&lightI=1.6&background=0,0,90');
  for (const m of METHODS) assert.equal(await page.locator(`.panel[data-method="${m}"] .raster`).innerText(), 'tiled');
  await page.getByLabel('Indexed palette').check();
  await quiet(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.palette.shades), 8);
  for (const m of METHODS) assert.equal(await page.locator(`.panel[data-method="${m}"] .raster`).innerText(), 'scanline', `${m} is drawn by the scanline rasterizer`);
  assert.match(await page.evaluate(() => window.shadelab.sceneToml('phong')), /rasterizer = "scanline"[\s\S]*palette_shades = 8\npalette_offset = 0/);
  assert.equal(await page.getByLabel('Rasterizer', { exact: true }).inputValue(), 'scanline');
  assert.ok(await page.locator('select[name="rasterizer"] option[value="tiled"]').evaluate((o) => o.disabled));
  for (const shades of [8, 4]) {
    if (shades !== 8) {
      await page.getByLabel('Shades (N) (number)').fill(String(shades));
      await page.getByLabel('Shades (N) (number)').press('Enter');
      await quiet(page);
    }
    const s = await statistics(page);
    assert.equal(s.gouraud.colours, shades, `Gouraud: ${s.gouraud.colours} colours`);
    assert.equal(s.phong.colours, shades, `Phong: ${s.phong.colours} colours`);
    assert.ok(s.flat.colours <= shades, `flat: ${s.flat.colours}`);
    if (shades === 8) {
      // The inspector names the palette entry it drew.
      await update(page, 's.pixel = [300, 240]');
      await page.evaluate(() => window.shadelab.setTab('inspector'));
      await quiet(page);
      const text = await page.evaluate(() => window.shadelab.inspection.text);
      assert.match(text, /Palette: intensity I = [\d.]+, shade k = min\(N − 1, ⌊I·8⌋\) = \d, entry 0 \+ \d = \d\./);
      await shot(page, 'palette.png', '.inspect-methods');
    }
  }
  // The panel is the command line's picture.
  const png = path.join(TMP, 'palette.png');
  shadelab('render', await sceneFile(page, 'palette.toml', 'phong'), '-o', png);
  assert.ok(Buffer.from((await decodePng(page, png)).rgba, 'base64').equals(await pixelsOf(page, 'phong')));
  // Off again: true colour, and back to the rasterizer chosen.
  await page.getByLabel('Indexed palette').uncheck();
  await quiet(page);
  assert.ok((await statistics(page)).phong.colours > 100);
  assert.equal(await page.locator('.panel[data-method="phong"] .raster').innerText(), 'tiled');
  assert.deepEqual(problems, []);
  await page.close();
});

test('fixed-point interpolation changes the picture; with 20 bits it is floating point within 1/255', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=12&interpolation=screen&polygons=whole');
  const float = { gouraud: await pixelsOf(page, 'gouraud'), phong: await pixelsOf(page, 'phong') };
  const before = await digests(page);
  await page.getByLabel('Fixed-point interpolation').check();
  await page.getByLabel('Fraction bits (number)').fill('4');
  await page.getByLabel('Fraction bits (number)').press('Enter');
  await quiet(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.fixedPoint), 4);
  const coarse = await digests(page);
  assert.notEqual(coarse.gouraud, before.gouraud);
  assert.notEqual(coarse.phong, before.phong);
  const png = path.join(TMP, 'fixed.png');
  shadelab('render', await sceneFile(page, 'fixed.toml', 'gouraud'), '-o', png);
  assert.ok(Buffer.from((await decodePng(page, png)).rgba, 'base64').equals(await pixelsOf(page, 'gouraud')), 'the panel is the command line’s picture');
  await update(page, 's.fixedPoint = 20');
  for (const m of ['gouraud', 'phong']) {
    const fine = await pixelsOf(page, m);
    let worst = 0;
    for (let i = 0; i < fine.length; i++) worst = Math.max(worst, Math.abs(fine[i] - float[m][i]));
    assert.ok(worst <= 1, `${m}: 20 fraction bits differ from floating point by ${worst}`);
  }
  // With 8 bits, along a row: the streaks of the stepped values, and their steps in the profile.
  await update(page, 's.fixedPoint = 8; s.profile = { row: 240 }');
  await page.evaluate(() => window.shadelab.setTab('profile'));
  await quiet(page);
  await shot(page, 'fixed-point.png', '.legend');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the quad study turns a quad: whole, its centre changes; as two triangles, it does not', async () => {
  const { page, problems } = await openViewer('#tab=quad&quadAngle=0');
  const at = async (angle) => {
    await page.getByLabel('Turn (°) (number)').fill(String(angle));
    await page.getByLabel('Turn (°) (number)').press('Enter');
    await quiet(page);
    return page.evaluate(() => window.shadelab.quad.quad);
  };
  const upright = await at(0);
  assert.ok(Math.abs(upright.whole_centre - 0.25) < 0.02, JSON.stringify(upright));
  assert.ok(Math.abs(upright.fans_centre - 0.5) < 0.02);
  const corner = await at(45);
  assert.ok(Math.abs(corner.whole_centre - 0.25) > 0.2, JSON.stringify(corner));
  assert.ok(Math.abs(corner.fans_centre - 0.5) < 0.02);
  assert.match(await page.locator('#tool-quad figure[data-kind="whole"] figcaption').innerText(), /centre: I = 0\.\d{3}/);
  await at(30);
  await shot(page, 'quad.png', '.quad-pictures');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the cost of each method: lighting evaluations per polygon, vertex and pixel, and the time', async () => {
  const { page, problems } = await openViewer('#tab=cost');
  const stats = await page.evaluate(() => Object.fromEntries(window.shadelab.panels.map((p) => [p.method, p.last])));
  // Flat evaluates once per polygon drawn, Phong once per pixel shaded, Gouraud once per vertex.
  assert.equal(stats.flat.stats.lighting_evaluations, stats.flat.stats.rasterized);
  assert.equal(stats.flat.cost.per_polygon, stats.flat.stats.lighting_evaluations);
  assert.equal(stats.phong.stats.lighting_evaluations, stats.phong.stats.fragments_shaded);
  assert.equal(stats.phong.cost.per_pixel, stats.phong.stats.lighting_evaluations);
  assert.equal(stats.gouraud.cost.per_vertex, stats.gouraud.stats.lighting_evaluations);
  assert.ok(stats.flat.stats.lighting_evaluations < stats.gouraud.stats.lighting_evaluations);
  assert.ok(stats.gouraud.stats.lighting_evaluations < stats.phong.stats.lighting_evaluations);
  const fmt = (n) => n.toLocaleString('en');
  for (const m of METHODS) {
    const row = page.locator(`#tool-cost tr[data-method="${m}"]`);
    assert.equal(await row.locator('td.evaluations .num').innerText(), fmt(stats[m].stats.lighting_evaluations));
  }
  assert.match(await page.locator('.panel[data-method="gouraud"] .stats').innerText(), /^2,082 lighting evaluations, one per vertex · 810 polygons drawn/);
  await page.getByRole('button', { name: /^Measure/ }).click();
  await page.waitForFunction(() => document.querySelectorAll('#tool-cost td.time .hint').length === 3, null, { timeout: 60000 });
  for (const m of METHODS) assert.match((await page.locator(`#tool-cost tr[data-method="${m}"] td.time`).innerText()).trim(), /^[\d.]+ \(fastest [\d.]+\)$/);
  await quiet(page);
  await shot(page, 'cost.png', 'table');
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- languages ----

const TABLES = {};
for (const lang of ['en', 'ru', 'sk', 'cs']) TABLES[lang] = (await import(path.join(ROOT, 'web/i18n', `${lang}.js`))).default;
const placeholders = (s) => [...s.matchAll(/\{(\w+)\}/g)].map((m) => m[1]).sort();
/** Strings that are the same in a translation: symbols, units, names. */
const SAME = {
  all: ['app.heading', 'color.r', 'color.g', 'color.b', 'model.summary'],
  sk: ['panel.time', 'inspector.pixel', 'profile.readout', 'group.model', 'model.source', 'quiz.panel'],
  cs: ['panel.time', 'inspector.pixel', 'profile.readout', 'group.model', 'model.source', 'quiz.panel', 'count.polygons.one'],
  ru: [],
};

test('the string tables are complete: every key, every placeholder, nothing left in English', () => {
  const en = TABLES.en;
  for (const lang of ['ru', 'sk', 'cs']) {
    const table = TABLES[lang];
    assert.deepEqual(Object.keys(table).sort(), Object.keys(en).sort(), `${lang}.js has the keys of en.js`);
    for (const [key, text] of Object.entries(table)) {
      assert.deepEqual(placeholders(text), placeholders(en[key]), `${lang} ${key}: placeholders`);
      const same = text === en[key];
      if (key !== 'app.locale') assert.equal(same, SAME.all.includes(key) || SAME[lang].includes(key), `${lang} ${key}: "${text}"`);
    }
    assert.equal(table['app.locale'], lang);
  }
});

/** Every piece of text on the page a reader meets: text nodes, titles, labels, placeholders. */
function pageWords() {
  const out = [];
  const walker = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT | NodeFilter.SHOW_ELEMENT);
  for (let n = walker.currentNode; n; n = walker.nextNode()) {
    if (n.nodeType === Node.ELEMENT_NODE) {
      if (['NOSCRIPT', 'SCRIPT', 'STYLE'].includes(n.tagName)) continue;
      for (const a of ['title', 'aria-label', 'placeholder', 'alt']) if (n.getAttribute(a)) out.push(n.getAttribute(a));
    } else if (!n.parentElement.closest('noscript, #language')) {
      if (n.textContent.trim()) out.push(n.textContent);
    }
  }
  out.push(document.title);
  return out;
}

const words = (texts) => new Set(texts.join(' ').match(/\p{L}{3,}/gu) ?? []);

test('switching the language changes every label and explanation; the choice is kept in the link', async () => {
  const { page, problems } = await openViewer('#model=sphere&pixel=260,200&row=200&errors=true&overlays.phong=wireframe');
  const labTexts = async (lang) => Object.values(await page.evaluate((l) => window.shadelab.panels[0].ask({ type: 'texts', lang: l }).then((r) => r.texts), lang));
  const englishVocabulary = words([...Object.values(TABLES.en), ...(await labTexts('en'))]);
  const english = await page.evaluate(pageWords);
  // The check sees the page: in English, hundreds of its words are the tables'.
  const seen = [...words(english)].filter((w) => englishVocabulary.has(w));
  assert.ok(seen.length > 250, `${seen.length} English words seen`);
  for (const lang of ['ru', 'sk', 'cs']) {
    await page.selectOption('#language', lang);
    await quiet(page);
    // Visit every tab, so that each instrument shows its content in the language.
    for (const tab of ['about', 'inspector', 'profile', 'errors', 'overlays', 'quad', 'cost']) {
      await page.locator(`#tab-${tab}`).click();
      await quiet(page);
    }
    assert.equal(await page.evaluate(() => document.documentElement.lang), lang);
    assert.match(await page.evaluate(() => location.hash), new RegExp(`lang=${lang}`));
    const ownVocabulary = words([...Object.values(TABLES[lang]), ...(await labTexts(lang))]);
    const leftover = [...words(await page.evaluate(pageWords))].filter((w) => englishVocabulary.has(w) && !ownVocabulary.has(w));
    assert.deepEqual(leftover, [], `${lang}: English words on the page`);
    // Every string from the tables changed: no text node is still an English string.
    const shown = new Set((await page.evaluate(pageWords)).map((s) => s.trim()));
    const untranslated = english.map((s) => s.trim()).filter((s) => s.length > 3 && /\p{L}{3}/u.test(s) && shown.has(s) && Object.values(TABLES.en).includes(s) && !Object.values(TABLES[lang]).includes(s));
    assert.deepEqual(untranslated, [], `${lang}: strings still in English`);
    await page.locator('#tab-inspector').click();
    await quiet(page);
    await shot(page, `language-${lang}.png`, '.inspect-methods');
  }
  // The link carries the language: a new page opens in Czech.
  const hash = await page.evaluate(() => location.hash);
  const again = await openViewer(hash);
  await quiet(again.page);
  assert.equal(await again.page.evaluate(() => document.documentElement.lang), 'cs');
  assert.equal(await again.page.locator('.panel[data-method="flat"] .title').innerText(), 'Konstantní');
  assert.deepEqual([...problems, ...again.problems], []);
  await Promise.all([page.close(), again.page.close()]);
});

test('without a language in the link, the page speaks the browser’s first language it knows', async () => {
  for (const [languages, expected] of [[['de-DE', 'sk-SK', 'en'], 'sk'], [['ru'], 'ru'], [['fr-FR'], 'en']]) {
    const page = await context.newPage();
    await page.addInitScript((l) => Object.defineProperty(navigator, 'languages', { get: () => l }), languages);
    const problems = [];
    page.on('pageerror', (e) => problems.push(e.message));
    await page.goto(baseUrl);
    await page.waitForFunction(() => window.shadelab?.panels.every((p) => p.frames > 0), null, { timeout: 60000 });
    assert.equal(await page.evaluate(() => document.documentElement.lang), expected, languages.join(','));
    assert.equal(await page.evaluate(() => window.shadelab.language), expected);
    assert.equal(await page.locator('#language').inputValue(), expected);
    // The browser's choice is not written into the link; a choice made on the page is.
    await settle(page);
    await page.evaluate(() => new Promise((r) => setTimeout(r, 300)));
    assert.doesNotMatch(await page.evaluate(() => location.hash), /lang=/);
    assert.deepEqual(problems, []);
    await page.close();
  }
});
