// The viewer in a classroom (issue 19): the quiz, a full round of it, and
// "Save animation", one orbit of the three panels as an animated PNG.
//
// Run with the other browser tests: (cd tests/browser && npm ci && npm test)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  useViewer, ARTIFACTS, METHODS,
  openViewer, settle, statistics, decodePng, shadelab, pixelsOf, until,
} from './harness.js';

useViewer();

const TMP = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-classroom-'));

// ---- 11. the quiz ----

test('the quiz runs a full round: the panels unlabelled and shuffled, four questions, an explanation after each', async () => {
  const { page, problems } = await openViewer('', { width: 1366, height: 768 });
  await page.getByRole('button', { name: 'Quiz' }).click();
  const letters = ['A', 'B', 'C'];
  const panelOf = (letter) => page.evaluate((l) => document.querySelector(`.panel[data-letter="${l}"]`).dataset.method, letter);
  /** Per letter: the statistics of the panel shown under it. */
  const byLetter = async () => {
    await until(page, () => window.shadelab.panels.every((p) => !p.busy && p.pending === null));
    await settle(page);
    const s = await statistics(page);
    const out = {};
    for (const l of letters) out[l] = s[await panelOf(l)];
    return out;
  };
  // The names are hidden; the order is shuffled into letters.
  assert.equal(await page.locator('.panel .title').first().evaluate((e) => getComputedStyle(e).visibility), 'hidden');
  assert.ok(await page.locator('#side').isHidden());
  await page.screenshot({ path: path.join(ARTIFACTS, 'quiz.png') });

  // 1. Which one is Gouraud? Not the faceted one (fewest colours), not the one with the highlight.
  assert.match(await page.locator('.quiz-question').textContent(), /Which one is Gouraud shading\?/);
  let s = await byLetter();
  const facets = letters.reduce((a, b) => (s[a].colours < s[b].colours ? a : b));
  const shiny = letters.reduce((a, b) => (s[a].maxGreen > s[b].maxGreen ? a : b));
  const gouraud = letters.find((l) => l !== facets && l !== shiny);
  await page.getByRole('button', { name: `Panel ${gouraud}` }).click();
  assert.equal(await page.locator('.quiz-verdict').textContent(), 'Right.');
  assert.match(await page.locator('.quiz-why').first().textContent(), /no highlight/);
  await page.getByRole('button', { name: 'Next question' }).click();

  // 2. Gouraud has its specular term too: Phong's highlight is the brighter, sharper one.
  assert.match(await page.locator('.quiz-question').textContent(), /Which panel is Phong shading\?/);
  s = await byLetter();
  const phong = letters.reduce((a, b) => (s[a].maxGreen > s[b].maxGreen ? a : b));
  assert.ok(s[phong].maxGreen >= 240);
  // Answer by clicking the panel itself.
  await page.locator(`.panel[data-letter="${phong}"] canvas`).click({ position: { x: 20, y: 20 } });
  await until(page, () => document.querySelector('.quiz-verdict')?.textContent === 'Right.');
  await page.getByRole('button', { name: 'Next question' }).click();

  // 3. Mach bands: a click on a polygon edge of the Gouraud panel, found where its intensity bends most.
  const question = await page.locator('.quiz-question').textContent();
  const letter = /^Panel ([ABC]) is Gouraud shading\. Where are the Mach bands\?/.exec(question)[1];
  const method = await panelOf(letter);
  assert.equal(method, 'gouraud');
  await byLetter();
  const px = await pixelsOf(page, 'gouraud');
  const row = 240;
  const I = (x) => { const i = (row * 480 + x) * 4; return px[i] + px[i + 1] + px[i + 2]; };
  let best = null;
  for (let x = 60; x < 420; x++) {
    if (!I(x - 3) || !I(x + 3)) continue;
    const bend = Math.abs((I(x + 3) - I(x)) - (I(x) - I(x - 3)));
    if (!best || bend > best.bend) best = { x, bend };
  }
  const canvas = page.locator(`.panel[data-letter="${letter}"] canvas`);
  const box = await canvas.boundingBox();
  await page.mouse.click(box.x + ((best.x + 0.5) * box.width) / 480, box.y + ((row + 0.5) * box.height) / 480);
  await until(page, () => document.querySelector('.quiz-verdict') !== null);
  assert.equal(await page.locator('.quiz-verdict').textContent(), 'Right.', `a click at x = ${best.x}`);
  assert.match(await page.locator('.quiz-why').first().textContent(), /changes its slope/);
  await page.getByRole('button', { name: 'Next question' }).click();

  // 4. Which weighting? Each panel is `shadelab render` of the quiz's scene with one weighting: find area's, answer another.
  assert.match(await page.locator('.quiz-question').textContent(), /weights each face’s normal by the face’s area\?/);
  await byLetter();
  const area = {};
  for (const l of letters) {
    const m = await panelOf(l);
    const scene = await page.evaluate((mm) => window.shadelab.panelScene(mm), m);
    const file = path.join(TMP, 'quiz-normals.toml');
    fs.writeFileSync(file, scene.replace(/normals = "\w+"/, 'normals = "area"'));
    shadelab('render', file, '-o', path.join(TMP, 'quiz-area.png'));
    const ref = Buffer.from((await decodePng(page, path.join(TMP, 'quiz-area.png'))).rgba, 'base64');
    const shown = await pixelsOf(page, m);
    let w = 0;
    for (let i = 0; i < shown.length; i++) w = Math.max(w, Math.abs(shown[i] - ref[i]));
    area[l] = w <= 1;
  }
  assert.equal(Object.values(area).filter(Boolean).length, 1, JSON.stringify(area));
  const right = letters.find((l) => area[l]);
  const wrong = letters.find((l) => !area[l]);
  await page.screenshot({ path: path.join(ARTIFACTS, 'quiz-normals.png') });
  await page.getByRole('button', { name: `Panel ${wrong}` }).click();
  assert.equal(await page.locator('.quiz-verdict').textContent(), `Not this one: it is panel ${right}.`);
  assert.match(await page.locator('.quiz-why').first().textContent(), /Weighted by area/);
  // The question and its explanation in the other languages.
  for (const [lang, words] of [['ru', /взвешена по её площади/], ['sk', /obsahom/], ['cs', /obsahem/]]) {
    await page.selectOption('#language', lang);
    await settle(page);
    assert.match(await page.locator('.quiz-question').textContent(), words, lang);
    assert.ok((await page.locator('.quiz-why').first().textContent()).length > 100, lang);
  }
  await page.selectOption('#language', 'en');
  await settle(page);
  await page.getByRole('button', { name: 'See the score' }).click();
  assert.equal(await page.locator('.quiz-score').textContent(), 'You answered 3 of 4 questions right.');
  await page.getByRole('button', { name: 'Leave the quiz' }).click();
  await settle(page);
  assert.ok(await page.locator('#side').isVisible());
  assert.equal(await page.locator('.panel[data-method="flat"] .title').evaluate((e) => getComputedStyle(e).visibility), 'visible');
  assert.deepEqual(problems, []);
  await page.close();
});

// ---- 12. Save animation ----

/** The chunks of a PNG file: [{type, data}]. */
function chunks(bytes) {
  assert.deepEqual([...bytes.subarray(0, 8)], [137, 80, 78, 71, 13, 10, 26, 10], 'a PNG signature');
  const out = [];
  for (let at = 8; at < bytes.length;) {
    const length = bytes.readUInt32BE(at);
    out.push({ type: bytes.toString('latin1', at + 4, at + 8), data: bytes.subarray(at + 8, at + 8 + length) });
    at += 12 + length;
  }
  return out;
}

test('Save animation writes one orbit of the three panels, labelled, as an animated PNG', async () => {
  const { page, problems } = await openViewer('#model=torus&pitch=25', { width: 1366, height: 768 });
  const frames = page.getByLabel('Animation frames (number)');
  await frames.fill('12');
  await frames.press('Enter');
  await settle(page);
  const [download] = await Promise.all([page.waitForEvent('download', { timeout: 300000 }), page.getByRole('button', { name: 'Save animation' }).click()]);
  assert.equal(download.suggestedFilename(), 'shadelab-orbit.apng');
  const file = path.join(ARTIFACTS, 'orbit.apng');
  await download.saveAs(file);
  const bytes = fs.readFileSync(file);
  const list = chunks(bytes);
  const ihdr = list.find((c) => c.type === 'IHDR').data;
  const [width, height] = [ihdr.readUInt32BE(0), ihdr.readUInt32BE(4)];
  assert.deepEqual([width, height], [3 * 480 + 2 * 4, 28 + 480]);
  const actl = list.find((c) => c.type === 'acTL').data;
  assert.equal(actl.readUInt32BE(0), 12, 'acTL: 12 frames');
  assert.equal(actl.readUInt32BE(4), 0, 'looping');
  const fctl = list.filter((c) => c.type === 'fcTL');
  assert.equal(fctl.length, 12);
  for (const f of fctl) {
    assert.deepEqual([f.data.readUInt32BE(4), f.data.readUInt32BE(8)], [width, height], 'every frame is whole');
    assert.equal(f.data.readUInt16BE(20) / f.data.readUInt16BE(22), 0.08, '80 ms a frame');
  }
  assert.equal(list.filter((c) => c.type === 'IDAT').length + list.filter((c) => c.type === 'fdAT').length, 12);
  await until(page, () => /Saved the animation: 12 frames of 1448 × 508 pixels\./.test(document.querySelector('#status').textContent));
  // Frame k (decoded by the browser) shows the panels at yaw 360·k/12, as `shadelab render` draws them.
  const decoded = await page.evaluate(async (b64) => {
    const data = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const decoder = new ImageDecoder({ data, type: 'image/png', colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
    await decoder.tracks.ready;
    const out = { count: decoder.tracks.selectedTrack.frameCount, frames: {} };
    for (const k of [0, 3]) {
      const { image } = await decoder.decode({ frameIndex: k });
      const canvas = new OffscreenCanvas(image.displayWidth, image.displayHeight);
      canvas.getContext('2d').drawImage(image, 0, 0);
      const d = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
      let s = '';
      for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode(...d.subarray(i, i + 0x8000));
      out.frames[k] = btoa(s);
      image.close();
    }
    return out;
  }, bytes.toString('base64'));
  assert.equal(decoded.count, 12);
  for (const k of [0, 3]) {
    const sheet = Buffer.from(decoded.frames[k], 'base64');
    for (const [i, m] of METHODS.entries()) {
      const scene = path.join(TMP, `orbit-${k}-${m}.toml`);
      const png = path.join(TMP, `orbit-${k}-${m}.png`);
      const text = await page.evaluate((mm) => window.shadelab.sceneToml(mm), m);
      fs.writeFileSync(scene, text.replace(/^yaw = .*$/m, `yaw = ${(360 * k) / 12}.0`));
      shadelab('render', scene, '-o', png);
      const ref = Buffer.from((await decodePng(page, png)).rgba, 'base64');
      let worst = 0;
      for (let y = 0; y < 480; y++) {
        for (let x = 0; x < 480; x++) {
          const a = ((28 + y) * width + i * 484 + x) * 4;
          const b = (y * 480 + x) * 4;
          for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(sheet[a + c] - ref[b + c]));
        }
      }
      assert.ok(worst <= 1, `frame ${k}, ${m}: differs from shadelab render by ${worst}`);
    }
  }
  // The panels are back as they were.
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), 0);
  assert.deepEqual(problems, []);
  await page.close();
});
