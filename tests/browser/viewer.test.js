// End-to-end tests of the viewer in headless Chromium (Debian's package),
// driven by playwright-core: the real `shadelab view` server, the real page,
// the real WebAssembly. Screenshots and measurements go to ./artifacts/.
// How the page draws (a file parsed once, three panels in one request, the
// frames' times): frames.test.js.
//
// Run from the repository root after `cargo build --release`:
//   (cd tests/browser && npm ci && npm test)
// SHADELAB_BIN names another binary; CHROMIUM another browser.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  useViewer, context, otherContext, baseUrl, BIN, ARTIFACTS, BUNNY, METHODS,
  openViewer, settle, update, digests, statistics, panelPixels, decodePng,
} from './harness.js';

useViewer();

test('the page loads with no console error, offline, and all three panels draw the model', async () => {
  const { page, problems } = await openViewer();
  const stats = await statistics(page);
  for (const m of METHODS) {
    assert.ok(stats[m].covered > 0.1 * 480 * 480, `${m} draws the teapot: ${JSON.stringify(stats[m])}`);
  }
  // One geometry, one rasterizer: the silhouettes are the same pixels.
  assert.equal(stats.flat.covered, stats.gouraud.covered);
  assert.equal(stats.gouraud.covered, stats.phong.covered);
  for (const m of METHODS) {
    const caption = await page.locator(`.panel[data-method="${m}"] .time-value`).textContent();
    assert.match(caption, /^\d+\.\d ms$/, `${m} shows its render time`);
    assert.match(await page.locator(`.panel[data-method="${m}"] .time-label`).textContent(), /^render, (3 panels at once, )?(last frame|median of \d)$/);
    const line = await page.locator(`.panel[data-method="${m}"] .stats`).textContent();
    assert.match(line, /lighting evaluations/);
  }
  // The picture for the README: steady-state times, not the first frame's.
  for (let i = 0; i < 15; i++) await update(page, `s.camera.yaw = ${i % 2 ? 0.01 : 0}`);
  await update(page, 's.camera.yaw = 0');
  await page.screenshot({ path: path.join(ARTIFACTS, 'viewer.png') });
  assert.deepEqual(problems, []);
  await page.close();
});

test('every control has a label and the panels take keyboard focus', async () => {
  const { page, problems } = await openViewer();
  const unlabelled = await page.evaluate(() =>
    [...document.querySelectorAll('input, select, button, canvas')]
      .filter((e) => !(e.labels?.length || e.getAttribute('aria-label') || e.textContent.trim()))
      .map((e) => e.outerHTML.slice(0, 80)),
  );
  assert.deepEqual(unlabelled, []);
  const canvas = page.locator('.panel[data-method="phong"] canvas');
  await canvas.focus();
  const before = await digests(page);
  await page.keyboard.press('ArrowRight');
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), -5);
  await page.keyboard.press('Shift+ArrowUp');
  await page.keyboard.press('+');
  await settle(page);
  const after = await digests(page);
  for (const m of METHODS) assert.notEqual(after[m], before[m], `${m} turned`);
  const state = await page.evaluate(() => window.shadelab.state);
  assert.ok(state.camera.zoom > 1);
  assert.ok(state.lights[0].position[1] > 2, 'Shift+Up raised the light');
  assert.deepEqual(problems, []);
  await page.close();
});

test('on a low-poly sphere flat shows facets, Phong a highlight that Gouraud lacks', async () => {
  const { page, problems } = await openViewer('#model=sphere');
  const s = await statistics(page);
  // Flat: one colour per visible facet (12 slices × 6 stacks: 72 faces, about
  // half of them visible), so few colours, each covering a large area.
  assert.ok(s.flat.colours <= 72, `flat has ${s.flat.colours} colours`);
  assert.ok(s.flat.covered / s.flat.colours > 2000, JSON.stringify(s.flat));
  assert.ok(s.gouraud.colours > 10 * s.flat.colours, `Gouraud is smooth: ${s.gouraud.colours} colours`);
  assert.ok(s.phong.colours > 10 * s.flat.colours, `Phong is smooth: ${s.phong.colours} colours`);
  // Kd = Ka = (200, 60, 60), white light, ambient 0.2: without the specular
  // term green never exceeds round((0.2 + 1) · 60) = 72; the highlight is white.
  assert.ok(s.gouraud.maxGreen <= 72, `Gouraud has no highlight: max green ${s.gouraud.maxGreen}`);
  assert.equal(s.gouraud.highlight, 0);
  assert.ok(s.phong.maxGreen >= 240, `Phong has a highlight: max green ${s.phong.maxGreen}`);
  assert.ok(s.phong.highlight > 100, `Phong's highlight covers ${s.phong.highlight} pixels`);
  // Phong's highlight is a spot, smaller than the facet flat shading lights up whole.
  assert.ok(s.phong.highlight < s.flat.highlight || s.flat.highlight === 0, JSON.stringify(s));
  await page.screenshot({ path: path.join(ARTIFACTS, 'sphere.png') });
  // With Gouraud's specular on, the highlight still falls inside a polygon,
  // between vertices that all miss it: the textbook failure of Gouraud shading.
  await update(page, 's.gouraudSpecular = true');
  const g = await statistics(page);
  assert.ok(g.gouraud.maxGreen < 150 && g.phong.maxGreen >= 240, JSON.stringify(g));
  assert.deepEqual(problems, []);
  await page.close();
});

test('a panel has the same pixels as `shadelab render` with the panel’s scene file', async () => {
  const { page, problems } = await openViewer('#model=torus&yaw=30&pitch=25&shininess=64&specular=blinn-phong');
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-scene-'));
  const report = {};
  for (const rasterizer of ['tiled', 'scanline']) {
    await update(page, `s.rasterizer = '${rasterizer}'`);
    for (const m of METHODS) {
      const scene = path.join(dir, `${m}.toml`);
      const png = path.join(dir, `${m}-${rasterizer}.png`);
      fs.writeFileSync(scene, await page.evaluate((mm) => window.shadelab.sceneToml(mm), m));
      execFileSync(BIN, ['render', scene, '-o', png], { stdio: 'pipe' });
      const cli = await decodePng(page, png);
      const panel = Buffer.from(await panelPixels(page, m), 'base64');
      const ref = Buffer.from(cli.rgba, 'base64');
      assert.equal(cli.width, 480);
      assert.equal(panel.length, ref.length);
      let differing = 0;
      let worst = 0;
      for (let i = 0; i < panel.length; i += 4) {
        const d = Math.max(Math.abs(panel[i] - ref[i]), Math.abs(panel[i + 1] - ref[i + 1]), Math.abs(panel[i + 2] - ref[i + 2]));
        if (d) differing += 1;
        worst = Math.max(worst, d);
      }
      report[`${rasterizer} ${m}`] = { differing, worst };
      // The browser runs the portable SIMD path, the CLI AVX2 with fused
      // multiply-adds where the CPU has it: they agree within 1/255.
      assert.ok(worst <= 1, `${rasterizer} ${m}: ${differing} pixels differ, by up to ${worst}`);
    }
  }
  fs.writeFileSync(path.join(ARTIFACTS, 'same-pixels.json'), JSON.stringify(report, null, 2));
  fs.rmSync(dir, { recursive: true, force: true });
  assert.deepEqual(problems, []);
  await page.close();
});

test('moving a slider changes all three pictures', async () => {
  const { page, problems } = await openViewer();
  const before = await digests(page);
  const slider = page.getByLabel('Shininess', { exact: true });
  await slider.focus();
  for (let i = 0; i < 10; i++) await page.keyboard.press('ArrowRight');
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.material.shininess), 42);
  const mid = await digests(page);
  // Flat and Phong show the specular term; Gouraud (without specular) does not.
  assert.notEqual(mid.flat, before.flat);
  assert.notEqual(mid.phong, before.phong);
  assert.equal(mid.gouraud, before.gouraud);
  const intensity = page.getByLabel('Intensity', { exact: true }).last();
  await intensity.focus();
  for (let i = 0; i < 20; i++) await page.keyboard.press('ArrowLeft');
  await settle(page);
  const after = await digests(page);
  for (const m of METHODS) assert.notEqual(after[m], mid[m], `${m} changed with the light's intensity`);
  assert.equal(await page.evaluate(() => window.shadelab.state.lights[0].intensity), 0.8);
  assert.match(await page.evaluate(() => window.shadelab.sceneToml('phong')), /\[\[lights\]\]\n(?:.*\n)*?intensity = 0\.8\n/);
  // Reset all brings back the defaults and their pictures.
  await page.getByRole('button', { name: 'Reset all' }).click();
  await settle(page);
  assert.deepEqual(await digests(page), before);
  assert.equal(await page.evaluate(() => location.hash), '');
  assert.deepEqual(problems, []);
  await page.close();
});

test('dragging on any panel rotates all three, the wheel zooms, Shift+drag moves the light', async () => {
  const { page, problems } = await openViewer();
  const before = await digests(page);
  const box = await page.locator('.panel[data-method="gouraud"] canvas').boundingBox();
  const cx = box.x + box.width / 2;
  const cy = box.y + box.height / 2;
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  for (let i = 1; i <= 10; i++) await page.mouse.move(cx + 8 * i, cy);
  await page.mouse.up();
  await settle(page);
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), -40);
  const turned = await digests(page);
  for (const m of METHODS) assert.notEqual(turned[m], before[m], `${m} rotated`);
  await page.screenshot({ path: path.join(ARTIFACTS, 'rotated.png') });

  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, -300);
  await settle(page);
  // Three notches of the wheel: 10 % each.
  const zoom = await page.evaluate(() => window.shadelab.state.camera.zoom);
  assert.ok(Math.abs(zoom - 1.1 ** 3) < 0.003, `zoomed in to ${zoom}`);

  const light = await page.evaluate(() => window.shadelab.state.lights[0].position);
  await page.keyboard.down('Shift');
  await page.mouse.move(cx, cy);
  await page.mouse.down();
  await page.mouse.move(cx - 60, cy + 10);
  await page.mouse.up();
  await page.keyboard.up('Shift');
  await settle(page);
  const moved = await page.evaluate(() => window.shadelab.state.lights[0].position);
  assert.notDeepEqual(moved, light);
  assert.ok(Math.abs(Math.hypot(...moved) - Math.hypot(...light)) < 0.01, 'the light turns about the model');
  assert.equal(await page.evaluate(() => window.shadelab.state.camera.yaw), -40, 'Shift+drag leaves the camera');
  assert.deepEqual(problems, []);
  await page.close();
});

test('a bad file shows a clear error and the previous model stays', async () => {
  const { page, problems } = await openViewer();
  const input = page.locator('input[type="file"]');
  // A good file first: an octahedron, by drag and drop onto the panels.
  const octahedron = 'v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n'
    + 'f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n';
  await page.evaluate((text) => {
    const dt = new DataTransfer();
    dt.items.add(new File([text], 'octahedron.obj'));
    const zone = document.querySelector('#panels');
    zone.dispatchEvent(new DragEvent('dragenter', { dataTransfer: dt, bubbles: true, cancelable: true }));
    zone.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, octahedron);
  await page.waitForFunction(() => window.shadelab.state.model === 'octahedron.obj');
  await settle(page);
  const good = await digests(page);
  const s = await statistics(page);
  assert.ok(s.flat.colours <= 4 && s.flat.covered > 20000, `the octahedron is drawn: ${JSON.stringify(s.flat)}`);

  const cases = [
    ['syntax.obj', 'v 1 2\nf 1 2 3\n', /syntax\.obj:1: .*3 coordinates/],
    ['empty.obj', '# nothing here\n', /empty\.obj: no faces/],
    ['nan.obj', 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n', /nan\.obj:1: .*not a finite number/],
    ['index.obj', 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n', /index\.obj:4/],
    ['photo.png', '\x89PNG\r\n\x1a\n', /photo\.png: unknown mesh format/],
    ['garbage.stl', 'this is not an STL file at all, not even close', /garbage\.stl/],
    ['garbage.ply', 'ply\nformat nonsense\n', /garbage\.ply/],
    ['garbage.glb', 'glTF????', /garbage\.glb/],
  ];
  for (const [name, text, expected] of cases) {
    await input.setInputFiles({ name, mimeType: 'application/octet-stream', buffer: Buffer.from(text, 'latin1') });
    await page.locator('#message').waitFor({ state: 'visible' });
    const message = await page.locator('#message .message-text').textContent();
    assert.match(message, expected, `${name}: ${message}`);
    assert.match(message, /the previous model stays/);
    assert.equal(await page.evaluate(() => window.shadelab.state.model), 'octahedron.obj', `${name} left the model alone`);
    await page.locator('#message .message-close').click();
  }
  await input.setInputFiles({ name: 'syntax.obj', mimeType: 'text/plain', buffer: Buffer.from('v 1 2\n') });
  await page.locator('#message').waitFor({ state: 'visible' });
  await page.screenshot({ path: path.join(ARTIFACTS, 'bad-file.png') });

  // A huge file is refused before it is read, with the limit stated.
  await page.evaluate(() => window.shadelab.openFile(new File([new Uint8Array(129 * 1024 * 1024)], 'huge.obj')));
  const huge = await page.locator('#message .message-text').textContent();
  assert.match(huge, /huge\.obj is 129\.0 MiB; the viewer reads files up to 128 MiB/);

  // The model and its pictures are the octahedron's still, and it still renders.
  await update(page, 's.camera.yaw = 0');
  assert.deepEqual(await digests(page), good);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the page exposes its test hooks only when the test asks for them', async () => {
  const plain = await otherContext({ viewport: { width: 1366, height: 768 } }, { hooks: false });
  const page = await plain.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(e.message));
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  await page.goto(baseUrl);
  // Drawn: each panel's canvas has pixels other than the background.
  await page.waitForFunction(() => [...document.querySelectorAll('.panel:not(.exact) canvas')].every((c) => {
    const d = c.getContext('2d', { willReadFrequently: true }).getImageData(0, 0, c.width, c.height).data;
    for (let i = 0; i < d.length; i += 4) if (d[i] !== d[0] || d[i + 1] !== d[1] || d[i + 2] !== d[2]) return true;
    return false;
  }), null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => typeof window.shadelab), 'undefined');
  assert.equal(await page.evaluate(() => Object.keys(window).filter((k) => /shadelab/i.test(k)).length), 0);
  // The keyboard works as ever without them.
  const first = await page.evaluate(() => document.querySelector('.panel canvas').toDataURL());
  await page.locator('.panel[data-method="flat"] canvas').focus();
  await page.keyboard.press('ArrowLeft');
  await page.waitForFunction((f) => document.querySelector('.panel canvas').toDataURL() !== f, first);
  assert.deepEqual(problems, []);
  await plain.close();
});

test('a scene the renderer refuses shows its message and the last pictures stay', async () => {
  const { page, problems } = await openViewer();
  const before = await digests(page);
  await update(page, 's.material.shininess = -1');
  await page.locator('#message').waitFor({ state: 'visible' });
  assert.match(await page.locator('#message .message-text').textContent(), /material\.shininess: must be 0\.\.=10000, got -1/);
  assert.deepEqual(await digests(page), before);
  await update(page, 's.material.shininess = 10');
  assert.ok(await page.locator('#message').isHidden(), 'the message goes with the next good frame');
  assert.deepEqual(problems, []);
  await page.close();
});

test('the exported PNG holds the three panels side by side', async () => {
  const { page, problems } = await openViewer('#model=icosphere&detail=2');
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Save PNG' }).click()]);
  const file = path.join(ARTIFACTS, 'export.png');
  await download.saveAs(file);
  assert.equal(download.suggestedFilename(), 'shadelab-flat-gouraud-phong.png');
  const png = await decodePng(page, file);
  assert.equal(png.width, 3 * 480 + 2 * 4);
  assert.equal(png.height, 28 + 480);
  const sheet = Buffer.from(png.rgba, 'base64');
  for (const [k, m] of METHODS.entries()) {
    const panel = Buffer.from(await panelPixels(page, m), 'base64');
    let mismatched = 0;
    for (let y = 0; y < 480; y++) {
      for (let x = 0; x < 480; x++) {
        const a = ((28 + y) * png.width + k * 484 + x) * 4;
        const b = (y * 480 + x) * 4;
        if (sheet[a] !== panel[b] || sheet[a + 1] !== panel[b + 1] || sheet[a + 2] !== panel[b + 2]) mismatched += 1;
      }
    }
    assert.equal(mismatched, 0, `panel ${k} of the PNG is the ${m} canvas`);
  }
  // The scene file beside it: what `shadelab compare` reads.
  const [sceneDownload] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Scene file' }).click()]);
  const scene = path.join(ARTIFACTS, 'scene.toml');
  await sceneDownload.saveAs(scene);
  const compare = path.join(ARTIFACTS, 'compare-from-scene.png');
  execFileSync(BIN, ['compare', scene, '-o', compare], { stdio: 'pipe' });
  const cli = await decodePng(page, compare);
  assert.equal(cli.width, png.width);
  assert.equal(cli.height, png.height);
  assert.deepEqual(problems, []);
  await page.close();
});

test('the exported static site works from another web server', async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-site-'));
  const site = path.join(dir, 'site');
  execFileSync(BIN, ['view', '--export', site], { stdio: 'pipe' });
  const types = { html: 'text/html', js: 'text/javascript', css: 'text/css', wasm: 'application/wasm', svg: 'image/svg+xml' };
  const { createServer } = await import('node:http');
  const other = createServer((req, res) => {
    const name = decodeURIComponent(new URL(req.url, 'http://x').pathname).replace(/^\/$/, '/index.html');
    const file = path.join(site, path.normalize(name));
    if (!file.startsWith(site) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'Content-Type': types[path.extname(file).slice(1)] ?? 'application/octet-stream' });
    res.end(fs.readFileSync(file));
  });
  await new Promise((resolve) => other.listen(0, '127.0.0.1', resolve));
  const page = await context.newPage();
  const problems = [];
  page.on('console', (m) => m.type() === 'error' && problems.push(m.text()));
  page.on('pageerror', (e) => problems.push(e.message));
  await page.goto(`http://127.0.0.1:${other.address().port}/#model=cube&yaw=30&pitch=20`);
  await page.waitForFunction(() => window.shadelab?.panels.every((p) => p.frames > 0), null, { timeout: 60000 });
  await settle(page);
  const s = await statistics(page);
  for (const m of METHODS) assert.ok(s[m].covered > 10000, `${m}: ${JSON.stringify(s[m])}`);
  assert.deepEqual(problems, []);
  await page.close();
  other.close();
  fs.rmSync(dir, { recursive: true, force: true });
});
