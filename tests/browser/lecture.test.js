// The viewer in a lecture hall and on a laptop (issue 19): the three panels
// stay in view while any control is used, Present fills the screen at the
// screen's own pixels, the captions say what they measure, the Cost tab's
// sentences are true of its numbers, the inspector's magnifier sits beside
// the pictures, plots are wide and labelled, a new model is framed and the
// wheel zooms by 10 %, counts are worded by each language's plural rules,
// and any number of lights of both kinds (the quiz and "Save animation":
// classroom.test.js).
// Screenshots for the README go to ./artifacts/ (docs/images/viewer-*.png
// are copies).
//
// Run with the other browser tests: (cd tests/browser && npm ci && npm test)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  useViewer, ARTIFACTS, METHODS,
  openViewer, otherContext, settle, quiet, update, digests, statistics, decodePng, median,
  shadelab, pixelsOf, until,
} from './harness.js';

useViewer();

const TMP = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-lecture-'));

/** The fraction of each panel canvas (by method) inside the viewport. */
async function panelsInView(page) {
  return page.evaluate(() => {
    const out = {};
    for (const c of document.querySelectorAll('.panel:not([hidden]) canvas')) {
      const r = c.getBoundingClientRect();
      const w = Math.max(0, Math.min(r.right, innerWidth) - Math.max(r.left, 0));
      const h = Math.max(0, Math.min(r.bottom, innerHeight) - Math.max(r.top, 0));
      out[c.closest('.panel').dataset.method] = r.width * r.height > 0 ? (w * h) / (r.width * r.height) : 0;
    }
    return out;
  });
}

/** The most pixels by which a panel differs from `shadelab render` of the panel's scene, per method. */
async function againstCli(page, name) {
  const worst = {};
  for (const m of METHODS) {
    const scene = path.join(TMP, `${name}-${m}.toml`);
    const png = path.join(TMP, `${name}-${m}.png`);
    fs.writeFileSync(scene, await page.evaluate((mm) => window.shadelab.sceneToml(mm), m));
    shadelab('render', scene, '-o', png);
    const ref = Buffer.from((await decodePng(page, png)).rgba, 'base64');
    const shown = await pixelsOf(page, m);
    assert.equal(shown.length, ref.length);
    let w = 0;
    for (let i = 0; i < shown.length; i++) w = Math.max(w, Math.abs(shown[i] - ref[i]));
    worst[m] = w;
  }
  return worst;
}

// ---- 1. the panels stay in view; 2. Present ----

test('at 1366×768 and 1920×1080 every control scrolled into view leaves each panel ≥ 90 % in view', async () => {
  for (const [name, viewport] of [['1366x768', { width: 1366, height: 768 }], ['1920x1080', { width: 1920, height: 1080 }]]) {
    const { page, problems } = await openViewer('', viewport);
    // Every control on show: four lights, fixed point and a palette (their rows appear), each tab in turn.
    await update(page, `
      s.lights.push({ ...s.lights[0], kind: 'directional', direction: [-1, -0.5, -1] }, { ...s.lights[0], position: [-2, 1, 2] }, { ...s.lights[0], on: false });
      s.fixedPoint = 8; s.palette = { shades: 8, offset: 0 };`);
    assert.equal(await page.evaluate(() => document.documentElement.scrollWidth), viewport.width, 'no horizontal scrolling');
    await page.screenshot({ path: path.join(ARTIFACTS, `layout-${name}.png`) });
    const seen = new Set();
    let worst = 1;
    for (const tab of ['about', 'inspector', 'profile', 'errors', 'overlays', 'quad', 'cost']) {
      await page.locator(`#tab-${tab}`).click();
      const count = await page.evaluate(() => {
        window.controlsToVisit = [...document.querySelectorAll('header button, header select, #controls-column input, #controls-column select, #controls-column button, #side input, #side select, #side button, #side summary')]
          .filter((e) => e.getClientRects().length > 0);
        return window.controlsToVisit.length;
      });
      for (let k = 0; k < count; k++) {
        const id = await page.evaluate((i) => {
          const e = window.controlsToVisit[i];
          e.scrollIntoView({ block: 'nearest', inline: 'nearest' });
          return e.id || `${e.tagName}:${e.name || e.getAttribute('aria-label') || e.textContent.trim().slice(0, 30)}:${i}`;
        }, k);
        seen.add(id);
        const inView = await panelsInView(page);
        for (const m of METHODS) {
          worst = Math.min(worst, inView[m]);
          assert.ok(inView[m] >= 0.9, `${name}, ${tab} tab, control ${id}: ${m} is ${(100 * inView[m]).toFixed(1)} % in view`);
        }
      }
    }
    // The page's own count of what was checked: the issue counted 63 controls.
    assert.ok(seen.size >= 63, `${name}: ${seen.size} controls visited`);
    // The panels are large: each at least 300 CSS pixels, side by side.
    const boxes = await page.locator('.panel:not([hidden]) canvas').evaluateAll((cs) => cs.map((c) => c.getBoundingClientRect().toJSON()));
    assert.ok(boxes.every((b) => b.width >= 300 && Math.abs(b.top - boxes[0].top) < 1), JSON.stringify(boxes));
    console.log(`${name}: ${seen.size} controls, each panel at least ${(100 * worst).toFixed(1)} % in view`);
    assert.deepEqual(problems, []);
    await page.close();
  }
});

test('on a narrow window the panels stack above the controls and stay in view while a slider moves', async () => {
  for (const viewport of [{ width: 800, height: 900 }, { width: 390, height: 844 }]) {
    const { page, problems } = await openViewer('', viewport);
    assert.ok(await page.evaluate(() => document.documentElement.scrollWidth) <= viewport.width, 'no horizontal scrolling');
    const sliders = await page.locator('#controls input[type="range"]').count();
    for (let k = 0; k < sliders; k++) {
      const slider = page.locator('#controls input[type="range"]').nth(k);
      if (!(await slider.isVisible())) continue;
      await slider.scrollIntoViewIfNeeded();
      const inView = await panelsInView(page);
      for (const m of METHODS) assert.ok(inView[m] >= 0.9, `${viewport.width}: slider ${k}: ${m} ${inView[m]}`);
    }
    // A slider moved by the keyboard changes the pictures in view.
    const before = await digests(page);
    await page.getByLabel('Shininess', { exact: true }).focus();
    for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
    await settle(page);
    assert.notEqual((await digests(page)).phong, before.phong);
    await page.screenshot({ path: path.join(ARTIFACTS, `layout-narrow-${viewport.width}.png`) });
    assert.deepEqual(problems, []);
    await page.close();
  }
});

/** Presents at `viewport` and device pixel ratio `dpr`; checks coverage and device pixels. */
async function presentAt(viewport, dpr) {
  const ctx = await otherContext({ viewport, deviceScaleFactor: dpr });
  try {
    const { page, problems } = await openViewer('', undefined, ctx);
    await page.getByRole('button', { name: 'Present' }).click();
    // The frames come at the new size: wait until each canvas holds its displayed size in device pixels.
    await until(page, () => window.shadelab.panels.every((p) => {
      const r = p.canvas.getBoundingClientRect();
      return p.canvas.width === Math.round(r.width * devicePixelRatio) && !p.busy && p.pending === null;
    }));
    const shown = await page.evaluate(() => window.shadelab.panels.map((p) => {
      const r = p.canvas.getBoundingClientRect();
      return { width: p.canvas.width, height: p.canvas.height, css: r.width, cssH: r.height, top: r.top, bottom: r.bottom, left: r.left, right: r.right };
    }));
    const area = shown.reduce((a, b) => a + b.css * b.cssH, 0) / (viewport.width * viewport.height);
    assert.ok(area >= 0.45, `${viewport.width}×${viewport.height} at dpr ${dpr}: the panels cover ${(100 * area).toFixed(1)} %`);
    for (const b of shown) {
      assert.equal(b.width, Math.round(b.css * dpr), `canvas ${b.width} for ${b.css} CSS pixels at dpr ${dpr}`);
      assert.equal(b.height, b.width);
      assert.ok(b.top >= 0 && b.bottom <= viewport.height && b.left >= 0 && b.right <= viewport.width, JSON.stringify(b));
    }
    assert.ok(await page.locator('#controls-column').isHidden(), 'the controls column is hidden');
    // The bar has the teacher's controls; the keyboard works on the panels.
    for (const label of ['Model', 'Dragging a panel moves', 'Shininess', 'Gouraud with specular']) {
      assert.ok(await page.locator('#present-bar').getByLabel(label, { exact: true }).first().isVisible(), label);
    }
    const yaw = await page.evaluate(() => window.shadelab.state.camera.yaw);
    await page.keyboard.press('ArrowRight');
    await settle(page);
    assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), yaw - 5, 'the arrow key orbits');
    if (dpr === 1) await page.screenshot({ path: path.join(ARTIFACTS, `present-${viewport.width}x${viewport.height}.png`) });
    await page.locator('#present-bar').getByLabel('Model', { exact: true }).selectOption('torus');
    await settle(page);
    const drawn = await statistics(page);
    assert.ok(drawn.phong.covered > 0.05 * shown[0].width ** 2, 'the torus is drawn at the large size');
    await page.keyboard.press('Escape');
    await until(page, () => !document.body.classList.contains('presenting') && window.shadelab.panels.every((p) => p.canvas.width === 480 && !p.busy));
    assert.ok(await page.locator('#controls-column').isVisible());
    assert.deepEqual(problems, []);
    return area;
  } finally {
    await ctx.close();
  }
}

test('Present covers at least 45 % of the screen with canvases drawn at device pixels (dpr 1 and 2)', async () => {
  const report = {};
  for (const viewport of [{ width: 1920, height: 1080 }, { width: 1366, height: 768 }]) {
    for (const dpr of [1, 2]) report[`${viewport.width}x${viewport.height}@${dpr}`] = await presentAt(viewport, dpr);
  }
  console.log('Present covers', JSON.stringify(report));
});

// ---- 3. captions; 4. the Cost tab ----

test('captions say what is timed (median of the last frames) and whether Gouraud has its specular term', async () => {
  const { page, problems } = await openViewer('#model=sphere');
  // As on two cores: panels that share a scene are drawn in one request.
  await page.evaluate(() => window.shadelab.drawTogether(true));
  for (let i = 0; i < 12; i++) await update(page, `s.camera.yaw = ${i}`);
  // Each panel's caption and its last 9 frame times.
  const captions = () => page.evaluate(() => Object.fromEntries(window.shadelab.panels.map((p) => [p.method, {
    label: p.figure.querySelector('.time-label').textContent,
    value: p.figure.querySelector('.time-value').textContent,
    title: p.figure.querySelector('.time').title,
    times: p.times.slice(-9),
  }])));
  const shown = await captions();
  // One scene, nothing else on the panels: the three were drawn in one call,
  // and the caption says so.
  for (const m of METHODS) {
    const s = shown[m];
    assert.equal(s.label, 'render, 3 panels at once, median of 9', m);
    assert.equal(s.value, `${median(s.times).toFixed(1)} ms`, `${m}: the median of the last 9 frames`);
    assert.deepEqual(s.times, shown.flat.times, `${m}: one time for the three`);
    assert.match(s.title, /drawn in one call, sharing the geometry .* the median of the last 9 frames, in one worker, or, on two cores, the slower of two workers that each drew half the rows at the same time\. The Cost tab times each method alone\./);
  }
  // With an overlay, each panel's worker draws its own method, and each caption
  // times it alone.
  await update(page, "s.overlays.phong = ['wireframe']");
  for (let i = 0; i < 12; i++) await update(page, `s.camera.yaw = ${20 + i}`);
  const apart = await captions();
  for (const m of METHODS) {
    const s = apart[m];
    assert.equal(s.label, 'render, median of 9', m);
    assert.equal(s.value, `${median(s.times).toFixed(1)} ms`, `${m}: the median of the last 9 frames`);
    assert.match(s.title, /in its worker, the median of the last 9 frames: reading the scene and drawing it, not the transfer/);
  }
  await update(page, 's.overlays.phong = []');
  const variant = page.locator('.panel[data-method="gouraud"] .variant');
  assert.equal(await variant.textContent(), 'no specular term');
  assert.equal(await page.locator('.panel[data-method="flat"] .variant').count(), 0);
  await page.getByLabel('Gouraud with specular', { exact: true }).check();
  await until(page, () => document.querySelector('.panel[data-method="gouraud"] .variant').textContent === 'specular at the vertices');
  assert.match(await variant.getAttribute('title'), /includes the specular term, evaluated at the vertices only/);
  await page.getByLabel('Gouraud with specular', { exact: true }).uncheck();
  await until(page, () => document.querySelector('.panel[data-method="gouraud"] .variant').textContent === 'no specular term');
  // The caption follows the frame shown: in Russian too.
  await page.selectOption('#language', 'ru');
  await settle(page);
  assert.equal(await variant.textContent(), 'без зеркальной составляющей');
  assert.match(await page.locator('.panel[data-method="phong"] .time-label').textContent(), /^отрисовка 3 панелей сразу, (последний кадр|медиана \d+ кадр(ов|а)?)$/);
  assert.deepEqual(problems, []);
  await page.close();
});

test('every sentence of the Cost tab is true of the numbers beside it', async () => {
  const { page, problems } = await openViewer('#tab=cost');
  await quiet(page);
  const read = () => page.evaluate(() => ({
    rows: Object.fromEntries(window.shadelab.panels.map((p) => {
      const row = document.querySelector(`#tool-cost tr[data-method="${p.method}"]`);
      return [p.method, {
        time: Number(row.querySelector('td.time .num').textContent),
        evaluations: Number(row.querySelector('td.evaluations .num').textContent.replace(/,/g, '')),
        where: row.querySelector('.where').textContent,
        stats: p.last.stats,
      }];
    })),
    sentences: Object.fromEntries([...document.querySelectorAll('#tool-cost [data-sentence]')].map((e) => [e.dataset.sentence, e.textContent])),
  }));
  let { rows, sentences } = await read();
  const { flat, gouraud, phong } = rows;
  // The counts are the frames' own.
  for (const m of METHODS) assert.equal(rows[m].evaluations, rows[m].stats.lighting_evaluations);
  assert.equal(flat.evaluations, flat.stats.rasterized, 'flat: once per polygon drawn');
  assert.equal(phong.evaluations, phong.stats.fragments_shaded, 'Phong: once per pixel shaded');
  assert.match(flat.where, new RegExp(`^once per polygon \\(${flat.stats.rasterized.toLocaleString('en')} polygons drawn\\)$`));
  // Gouraud on the tiled rasterizer lights every vertex normal of the mesh: turning the camera changes nothing…
  assert.match(gouraud.where, /of the whole mesh, drawn or not/);
  await update(page, 's.camera.yaw = 150; s.camera.pitch = 40');
  await quiet(page);
  assert.equal((await read()).rows.gouraud.evaluations, gouraud.evaluations, 'tiled: the same count from another side');
  // …and with back faces drawn, twice as many.
  await update(page, 's.cull = false');
  await quiet(page);
  assert.equal((await read()).rows.gouraud.evaluations, 2 * gouraud.evaluations, 'tiled: twice with back faces drawn');
  // The scanline rasterizer culls a polygon before it lights its corners:
  // fewer than the whole mesh's, more with back faces drawn.
  await update(page, "s.cull = true; s.rasterizer = 'scanline'; s.camera.yaw = 0; s.camera.pitch = 0");
  await quiet(page);
  ({ rows, sentences } = await read());
  assert.match(rows.gouraud.where, /culls a polygon before lighting its corners/);
  const front = rows.gouraud.evaluations;
  assert.ok(front > 0 && front < gouraud.evaluations, `scanline: ${front} corners lit, fewer than the mesh's ${gouraud.evaluations}`);
  await update(page, 's.cull = false');
  await quiet(page);
  assert.ok((await read()).rows.gouraud.evaluations > front, 'scanline: back faces drawn are lit too');
  await update(page, 's.cull = true');
  await quiet(page);
  await update(page, 's.camera.yaw = 0; s.camera.pitch = 0');
  await quiet(page);
  ({ rows, sentences } = await read());
  // The ratios are those of the numbers in the table.
  const ratio = (a, b) => (a / b).toFixed(1);
  assert.equal(sentences['cost.evaluationRatio'], `In these frames Gouraud evaluated the model ${ratio(rows.gouraud.evaluations, rows.flat.evaluations)} times as often as flat, Phong ${ratio(rows.phong.evaluations, rows.flat.evaluations)} times as often.`);
  const times = await page.evaluate(() => Object.fromEntries(window.shadelab.panels.map((p) => [p.method, p.times.slice(-30)])));
  const t = Object.fromEntries(METHODS.map((m) => [m, median(times[m])]));
  for (const m of METHODS) assert.equal(rows[m].time.toFixed(1), t[m].toFixed(1), `${m}: the time shown is the median of the last frames`);
  assert.equal(sentences['cost.timeRatio'], `In these times Gouraud took ${ratio(t.gouraud, t.flat)} times as long as flat, Phong ${ratio(t.phong, t.flat)} times as long.`);
  const ps = rows.phong.stats;
  assert.equal(sentences['cost.overdraw'].startsWith(`Phong: ${ps.fragments_shaded.toLocaleString('en')} pixels shaded, ${ps.covered_pixels.toLocaleString('en')} pixels covered; `), true, sentences['cost.overdraw']);
  assert.match(sentences['cost.overdraw'], ps.fragments_shaded > ps.covered_pixels ? /shaded again/ : /no pixel was shaded twice/);
  assert.match(sentences['cost.frame'], new RegExp(`^One frame: ${rows.flat.stats.rasterized.toLocaleString('en')} polygons drawn, ${rows.flat.stats.culled.toLocaleString('en')} culled as back faces, scanline rasterizer\\.$`));
  // No sentence speaks of what the numbers do not show.
  const all = await page.locator('#tool-cost').innerText();
  assert.doesNotMatch(all, /GPU|hardware|faster on|only grow/i);
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- 5. the inspector; 6. plots ----

test('the inspector magnifies 15 × 15 pixels 8× beside the panels, and no label covers a picture', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=8&tab=inspector&pixel=250,200', { width: 1366, height: 768 });
  await quiet(page);
  const mags = page.locator('#tool-inspector canvas.magnifier');
  assert.equal(await mags.count(), 3);
  await page.locator('#tool-inspector .inspect-methods').scrollIntoViewIfNeeded();
  const boxes = await mags.evaluateAll((cs) => cs.map((c) => c.getBoundingClientRect().toJSON()));
  const panels = await page.locator('.panel canvas').evaluateAll((cs) => cs.map((c) => c.getBoundingClientRect().toJSON()));
  const overlap = (a, b) => a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom;
  for (const b of boxes) {
    assert.equal(Math.round(b.width), 120);
    assert.equal(Math.round(b.height), 120);
    for (const p of panels) assert.ok(!overlap(b, p), 'the magnifier is beside the panels, not over them');
  }
  // Its middle cell is the inspected pixel, its neighbours the neighbours.
  for (const m of METHODS) {
    const px = await pixelsOf(page, m);
    const cells = await page.locator(`#tool-inspector article[data-method="${m}"] canvas.magnifier`).evaluate((c) => {
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const k = c.width / 15;
      const at = (i, j) => {
        const o = (Math.floor((j + 0.5) * k) * c.width + Math.floor((i + 0.5) * k)) * 4;
        return [d[o], d[o + 1], d[o + 2]];
      };
      return { centre: at(7, 7), right: at(8, 7), up: at(7, 6) };
    });
    const pixel = (x, y) => [...px.subarray((y * 480 + x) * 4, (y * 480 + x) * 4 + 3)];
    assert.deepEqual(cells.centre, pixel(250, 200), `${m}: the middle of the magnifier`);
    assert.deepEqual(cells.right, pixel(251, 200), `${m}: right of it`);
    assert.deepEqual(cells.up, pixel(250, 199), `${m}: above it`);
  }
  assert.match(await page.locator('#tool-inspector figcaption').first().textContent(), /^8× of the 15 × 15 pixels around \(250, 200\)$/);
  // The vertex letters and P, Q are in the diagram beside, not on the panels.
  assert.equal(await page.locator('.panel svg.marks > text').count(), 0, 'no text over the pictures');
  assert.ok(await page.locator('#tool-inspector svg.diagram text').count() >= 5, 'the diagram letters the polygon, P, Q and O');
  // Pointing at a panel moves the magnifiers there.
  const box = await page.locator('.panel[data-method="phong"] canvas').boundingBox();
  await page.mouse.move(box.x + (100.5 * box.width) / 480, box.y + (300.5 * box.height) / 480);
  await until(page, () => document.querySelector('#tool-inspector figcaption').textContent.includes('(100, 300)'));
  await page.screenshot({ path: path.join(ARTIFACTS, 'inspector-magnifier.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('the profile plots use the width under the panels and label their axes with units', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=10&row=230&tab=profile', { width: 1366, height: 768 });
  await quiet(page);
  const sizes = await page.evaluate(() => ({
    side: document.querySelector('#side').clientWidth,
    plots: [...document.querySelectorAll('#tool-profile canvas.plot')].map((c) => ({ width: c.getBoundingClientRect().width, x: c.dataset.xLabel, y: c.dataset.yLabel, font: parseFloat(getComputedStyle(c).fontSize) })),
  }));
  assert.equal(sizes.plots.length, 2);
  for (const p of sizes.plots) {
    assert.ok(p.width >= 0.9 * sizes.side && p.width >= 900, `a plot ${p.width} pixels wide of ${sizes.side}`);
    assert.match(p.x, /\(pixels\)/);
    assert.match(p.y, /0–255/);
    assert.ok(p.font >= 13, `type of ${p.font} pixels`);
  }
  await page.locator('#tool-profile canvas.plot-intensity').scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(ARTIFACTS, 'profile-wide.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- 7. framing and zoom ----

test('a loaded model is framed, a double click resets the camera, the wheel zooms 10 % a notch within limits', async () => {
  const { page, problems } = await openViewer();
  const canvas = page.locator('.panel[data-method="phong"] canvas');
  const box = await canvas.boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  // The limits are render.zoom's range in the core's table (params.json), as for a scene file.
  for (let i = 0; i < 60; i++) await page.mouse.wheel(0, -100);
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.zoom), 100, 'the zoom stops at 100×');
  for (let i = 0; i < 90; i++) await page.mouse.wheel(0, 100);
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.zoom), 0.1, 'and at a tenth');
  await page.mouse.wheel(0, -100);
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.zoom), 0.11, 'one notch: 10 %');
  await canvas.dblclick({ position: { x: 5, y: 5 } });
  await settle(page);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.camera), { yaw: 0, pitch: 0, zoom: 1 });

  // Far off and close in, then a new file: it is framed, whole and large.
  await update(page, 's.camera = { yaw: 140, pitch: -60, zoom: 6 }');
  const obj = 'v 10 10 10\nv 14 10 10\nv 10 13 10\nv 10 10 16\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n';
  await page.locator('input[type="file"]').setInputFiles({ name: 'far.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) });
  await until(page, () => window.shadelab.state.model === 'far.obj' && window.shadelab.panels.every((p) => !p.busy && p.pending === null && p.last));
  await settle(page);
  assert.deepEqual(await page.evaluate(() => window.shadelab.state.camera), { yaw: 0, pitch: 0, zoom: 1 });
  const extent = await page.evaluate(() => {
    const p = window.shadelab.panels[2];
    const d = p.context.getImageData(0, 0, 480, 480).data;
    let [x0, y0, x1, y1] = [480, 480, -1, -1];
    for (let y = 0; y < 480; y++) for (let x = 0; x < 480; x++) {
      const i = (y * 480 + x) * 4;
      if (d[i] || d[i + 1] || d[i + 2]) { x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y); }
    }
    return { x0, y0, x1, y1 };
  });
  // Inside the panel with a margin, and no dot: it spans a good part of it.
  assert.ok(extent.x0 > 5 && extent.y0 > 5 && extent.x1 < 474 && extent.y1 < 474, JSON.stringify(extent));
  assert.ok(Math.max(extent.x1 - extent.x0, extent.y1 - extent.y0) > 0.4 * 480, JSON.stringify(extent));
  // The status line counts by the language's rules.
  assert.equal(await page.locator('#status').textContent(), 'far.obj: 4 vertices, 4 polygons (4 triangles)');
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- 9. texts ----

test('counts follow each language’s plural rules and no label is cut off', async () => {
  const { page, problems } = await openViewer('', { width: 1366, height: 768 });
  const one = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n';
  await page.locator('input[type="file"]').setInputFiles({ name: 'one.obj', mimeType: 'text/plain', buffer: Buffer.from(one) });
  await until(page, () => window.shadelab.state.model === 'one.obj');
  await settle(page);
  const expected = {
    en: ['one.obj: 3 vertices, 1 polygon (1 triangle)', /^1 lighting evaluation, one per polygon · 1 polygon drawn · [\d,]+ pixels shaded$/],
    ru: ['one.obj: 3 вершины, 1 многоугольник (1 треугольник)', /^1 вычисление освещения, по одному на многоугольник · нарисован 1 многоугольник · закрашено [\d\s\u00a0\u202f]+ пикс/],
    sk: ['one.obj: 3 vrcholy, 1 polygón (1 trojuholník)', /^1 vyhodnotenie osvetlenia, jedno na polygón · 1 vykreslený polygón · [\d\s\u00a0\u202f]+ vytieňovaných pixelov$/],
    cs: ['one.obj: 3 vrcholy, 1 polygon (1 trojúhelník)', /^1 vyhodnocení osvětlení, jedno na polygon · 1 vykreslený polygon · [\d\s\u00a0\u202f]+ vystínovaných pixelů$/],
  };
  for (const lang of ['en', 'ru', 'sk', 'cs']) {
    await page.selectOption('#language', lang);
    await quiet(page);
    // The model's summary is said again in the language when the model is chosen.
    await page.evaluate(() => window.shadelab.setModel('one.obj'));
    await settle(page);
    assert.equal(await page.locator('#status').textContent(), expected[lang][0]);
    assert.match(await page.locator('.panel[data-method="flat"] .stats').textContent(), expected[lang][1]);
    // Every label of the controls and the tabs shows all of its text.
    const cut = await page.evaluate(() => [...document.querySelectorAll('#controls-column label, #controls-column legend, #side label, .tabs button, header button, .panel figcaption > *')]
      .filter((e) => e.getClientRects().length && (e.scrollWidth > e.clientWidth + 1 || e.scrollHeight > e.clientHeight + 1))
      .map((e) => `${e.textContent} (${e.scrollWidth}>${e.clientWidth})`));
    assert.deepEqual(cut, [], `${lang}: labels cut off`);
    if (lang === 'sk') await page.screenshot({ path: path.join(ARTIFACTS, 'slovak.png') });
  }
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- 10. lights ----

test('four lights of both kinds light the panels as `shadelab render` does; markers drag them; links keep them', async () => {
  const { page, problems } = await openViewer('#model=sphere&detail=24', { width: 1366, height: 768 });
  // Three more lights from the page's controls: two of them directional.
  for (let i = 0; i < 3; i++) await page.getByRole('button', { name: 'Add a light' }).click();
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.lights.length), 4);
  await page.getByLabel('Kind').nth(1).selectOption('directional');
  await page.getByLabel('Kind').nth(3).selectOption('directional');
  await settle(page);
  // Colours: white, red, green, blue.
  await update(page, `
    s.lights[0].position = [2, 2, 3];
    s.lights[1].color = [255, 0, 0]; s.lights[1].direction = [1, 0, -0.2];
    s.lights[2].color = [0, 255, 0]; s.lights[2].position = [0, 3, 1];
    s.lights[3].color = [0, 0, 255]; s.lights[3].direction = [0, 1, -0.3];`);
  const scene = await page.evaluate(() => window.shadelab.sceneToml('phong'));
  assert.equal((scene.match(/\[\[lights\]\]/g) ?? []).length, 4);
  assert.equal((scene.match(/kind = "directional"/g) ?? []).length, 2);
  let worst = await againstCli(page, 'four-lights');
  for (const m of METHODS) assert.ok(worst[m] <= 1, `four lights, ${m}: ${worst[m]}`);
  await page.screenshot({ path: path.join(ARTIFACTS, 'lights.png') });
  const four = await digests(page);
  // Each light adds light: turning one off darkens the picture, and it is `shadelab render`'s again.
  const sum = async () => { const p = await pixelsOf(page, 'phong'); let t = 0; for (let i = 0; i < p.length; i += 4) t += p[i] + p[i + 1] + p[i + 2]; return t; };
  const all = await sum();
  for (const k of [0, 1, 2, 3]) {
    await page.getByLabel(`Light ${k + 1}`, { exact: true }).uncheck();
    await settle(page);
    assert.ok((await sum()) < all, `light ${k + 1} off: darker`);
    worst = await againstCli(page, `light-${k}-off`);
    for (const m of METHODS) assert.ok(worst[m] <= 1, `light ${k + 1} off, ${m}: ${worst[m]}`);
    await page.getByLabel(`Light ${k + 1}`, { exact: true }).check();
    await settle(page);
  }
  assert.deepEqual(await digests(page), four);
  // With every light off only the ambient term is left: Ia·Ka = 0.2 · (200, 60, 60), everywhere.
  await update(page, 's.lights.forEach((l) => (l.on = false))');
  assert.match(await page.evaluate(() => window.shadelab.sceneToml('flat')), /^lights = \[\]/);
  const s = await statistics(page);
  for (const m of METHODS) assert.equal(s[m].colours, 1, `${m}: ambient only`);
  const px = await pixelsOf(page, 'gouraud');
  const k = (240 * 480 + 240) * 4;
  assert.deepEqual([px[k], px[k + 1], px[k + 2]], [40, 12, 12]);
  await update(page, 's.lights.forEach((l) => (l.on = true))');

  // Dragging light 2's marker to the panel's centre puts the light behind the camera: its rays travel along −z.
  const marker = await page.evaluate(() => {
    const g = document.querySelector('.panel[data-method="gouraud"] svg.marks g.mark-light[data-light="1"] circle');
    const r = g.getBoundingClientRect();
    return { x: r.x + r.width / 2, y: r.y + r.height / 2 };
  });
  const box = await page.locator('.panel[data-method="gouraud"] canvas').boundingBox();
  await page.mouse.move(marker.x, marker.y);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(marker.x + ((box.x + box.width / 2 - marker.x) * i) / 10, marker.y + ((box.y + box.height / 2 - marker.y) * i) / 10);
  await page.mouse.up();
  await settle(page);
  const dragged = await page.evaluate(() => window.shadelab.state.lights[1]);
  const len = Math.hypot(1, 0, -0.2);
  assert.ok(Math.abs(dragged.direction[0]) < 0.05 * len && Math.abs(dragged.direction[1]) < 0.05 * len && Math.abs(dragged.direction[2] + len) < 0.05 * len, JSON.stringify(dragged));
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), 0, 'dragging a marker leaves the camera');
  worst = await againstCli(page, 'dragged');
  for (const m of METHODS) assert.ok(worst[m] <= 1, `after the drag, ${m}: ${worst[m]}`);

  // The link carries the lights; the scene file too.
  await page.waitForFunction(() => location.hash.includes('lights='));
  const hash = await page.evaluate(() => location.hash);
  const again = await openViewer(hash);
  const active = (lights) => lights.map((l) => ({ on: l.on, kind: l.kind, color: l.color, intensity: l.intensity, v: l.kind === 'point' ? l.position : l.direction }));
  assert.deepEqual(active(await again.page.evaluate(() => window.shadelab.state.lights)), active(await page.evaluate(() => window.shadelab.state.lights)));
  assert.deepEqual(await digests(again.page), await digests(page));
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Scene file' }).click()]);
  const file = path.join(TMP, 'lights-scene.toml');
  await download.saveAs(file);
  shadelab('compare', file, '-o', path.join(TMP, 'lights-compare.png'));
  // A link made before the page had several lights still means what it meant.
  const old = await openViewer('#light=255,240,200&lightI=1.4&lightPos=-2,3,1.5');
  assert.deepEqual(await old.page.evaluate(() => window.shadelab.state.lights), [{ on: true, kind: 'point', color: [255, 240, 200], intensity: 1.4, position: [-2, 3, 1.5], direction: [-1, -1, -1], attenuation: [1, 0, 0] }]);
  assert.deepEqual([...problems, ...again.problems, ...old.problems], []);
  await Promise.all([page.close(), again.page.close(), old.page.close()]);
});

// ---- the README's pictures ----

test('screenshots at 1366×768 and 1920×1080 for the README', async () => {
  // Steady-state times in the captions, not the first frame's: a few frames first.
  const warm = async (page, yaw) => {
    for (let i = 0; i < 12; i++) await update(page, `s.camera.yaw = ${yaw + (i % 2 ? 0.01 : 0)}`);
    await update(page, `s.camera.yaw = ${yaw}`);
    await quiet(page);
  };
  const laptop = await openViewer('#tab=inspector&pixel=262,236', { width: 1366, height: 768 });
  await warm(laptop.page, 0);
  await laptop.page.screenshot({ path: path.join(ARTIFACTS, 'viewer-1366x768.png') });
  const projector = await openViewer('#model=torus&detail=32&yaw=20&pitch=30&tab=cost&lights='
    + encodeURIComponent('point:2,2,3:255,255,255:0.8;directional:1,0.2,-0.4:255,80,80:0.7;point:-2,3,-1:80,255,80:0.6;directional:-0.3,-1,-0.6:90,120,255:0.8'),
  { width: 1920, height: 1080 });
  await warm(projector.page, 20);
  assert.equal(await projector.page.evaluate(() => window.shadelab.state.lights.length), 4);
  await projector.page.screenshot({ path: path.join(ARTIFACTS, 'viewer-1920x1080.png') });
  assert.deepEqual([...laptop.problems, ...projector.problems], []);
  await Promise.all([laptop.page.close(), projector.page.close()]);
});
