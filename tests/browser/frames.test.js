// How the viewer draws, in headless Chromium (as viewer.test.js): a user's
// file is parsed once and its mesh handed to the other panels; the three
// panels of one scene are drawn in one request (in parts of their rows on
// two cores); the first view is drawn again while the engine warms up; a
// frame leaves the page's thread alone while it is drawn; and the frames'
// times. Measurements go to ./artifacts/.
//
// Run from the repository root after `cargo build --release`:
//   (cd tests/browser && npm ci && npm test)
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  useViewer, BIN, ARTIFACTS, BUNNY, METHODS,
  openViewer, settle, update, digests, panelPixels, decodePng, median, percentile,
} from './harness.js';

useViewer();

/** A UV sphere as OBJ text, with a normal of its own length at every vertex and two smoothing groups. */
function sphereObj(slices = 20, stacks = 12) {
  const lines = [];
  for (let j = 0; j <= stacks; j++) {
    for (let i = 0; i < slices; i++) {
      const t = (Math.PI * j) / stacks;
      const p = (2 * Math.PI * i) / slices;
      const v = [Math.sin(t) * Math.cos(p), Math.cos(t), Math.sin(t) * Math.sin(p)];
      lines.push(`v ${v.map((x) => x.toFixed(6)).join(' ')}`);
      // Normals of all sorts of lengths: the renderer normalises them.
      lines.push(`vn ${v.map((x) => (x * (0.3 + ((i * 7 + j) % 5))).toFixed(6)).join(' ')}`);
    }
  }
  const at = (j, i) => j * slices + (i % slices) + 1;
  for (let j = 0; j < stacks; j++) {
    if (j === stacks / 2) lines.push('s 2');
    else if (j === 0) lines.push('s 1');
    for (let i = 0; i < slices; i++) {
      const q = [at(j, i), at(j + 1, i), at(j + 1, i + 1), at(j, i + 1)];
      lines.push(`f ${q.map((k) => `${k}//${k}`).join(' ')}`);
    }
  }
  return `${lines.join('\n')}\n`;
}

test('a file is parsed once: one panel parses it, the others take its mesh, and all three draw what `shadelab render` draws', async () => {
  const { page, problems } = await openViewer();
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-once-'));
  const obj = path.join(dir, 'ball.obj');
  fs.writeFileSync(obj, sphereObj());
  const before = await page.evaluate(() => window.shadelab.counts());
  await page.locator('input[type="file"]').setInputFiles(obj);
  await page.waitForFunction(() => window.shadelab.state.model === 'ball.obj');
  await settle(page);
  const loaded = await page.evaluate(() => window.shadelab.counts());
  const added = (key) => Object.fromEntries(METHODS.map((m) => [m, loaded[m][key] - before[m][key]]));
  assert.deepEqual(added('files_parsed'), { flat: 1, gouraud: 0, phong: 0 });
  assert.deepEqual(added('files_adopted'), { flat: 0, gouraud: 1, phong: 1 });
  // The file's normals are used (auto), and every panel is the command line's picture.
  await update(page, 's.camera.yaw = 25; s.camera.pitch = 15');
  for (const m of METHODS) {
    const scene = path.join(dir, `${m}.toml`);
    const png = path.join(dir, `${m}.png`);
    fs.writeFileSync(scene, await page.evaluate((mm) => window.shadelab.sceneToml(mm), m));
    assert.match(fs.readFileSync(scene, 'utf8'), /source = "ball\.obj"/);
    execFileSync(BIN, ['render', scene, '-o', png], { stdio: 'pipe' });
    const cli = Buffer.from((await decodePng(page, png)).rgba, 'base64');
    const panel = Buffer.from(await panelPixels(page, m), 'base64');
    assert.equal(panel.length, cli.length);
    let worst = 0;
    for (let i = 0; i < panel.length; i += 4) {
      worst = Math.max(worst, Math.abs(panel[i] - cli[i]), Math.abs(panel[i + 1] - cli[i + 1]), Math.abs(panel[i + 2] - cli[i + 2]));
    }
    assert.ok(worst <= 1, `${m}: differs from shadelab render by up to ${worst}`);
  }
  // Orbiting draws; it neither parses nor prepares the model, nor reads the scene text again.
  await page.evaluate(() => window.shadelab.drawTogether(true, 2));
  await settle(page);
  const still = await page.evaluate(() => window.shadelab.counts());
  await page.locator('.panel[data-method="phong"] canvas').focus();
  for (let k = 0; k < 3; k++) {
    await page.keyboard.press('ArrowRight');
    await settle(page);
  }
  const orbited = await page.evaluate(() => window.shadelab.counts());
  // The three panels share the scene: as on two cores, the first two
  // panels' workers each draw half the rows of the three methods of each
  // frame in one call, the third rests.
  const drawn = { flat: 3, gouraud: 3, phong: 0 };
  for (const m of METHODS) {
    assert.equal(orbited[m].files_parsed + orbited[m].files_adopted, still[m].files_parsed + still[m].files_adopted, m);
    assert.equal(orbited[m].models_prepared, still[m].models_prepared, `${m}: the model was prepared again`);
    assert.equal(orbited[m].frames - still[m].frames, 3 * drawn[m], `${m}: three frames (or their halves) per key`);
    assert.equal(orbited[m].camera_turns - still[m].camera_turns, drawn[m], `${m}: the camera turned`);
    assert.equal(orbited[m].scenes_read, still[m].scenes_read, `${m}: the scene text was read again`);
  }
  fs.rmSync(dir, { recursive: true, force: true });
  assert.deepEqual(problems, []);
  await page.close();
});

test('the three panels of one scene are drawn in one request, with the pixels of three', async () => {
  const { page, problems } = await openViewer('#model=torus&yaw=20&pitch=15&shininess=48');
  // As on one core: the first panel's worker draws the three frames whole.
  await page.evaluate(() => window.shadelab.drawTogether(true, 1));
  await settle(page);
  const frames = async () => {
    const c = await page.evaluate(() => window.shadelab.counts());
    return Object.fromEntries(METHODS.map((m) => [m, c[m].frames]));
  };
  /** Each worker's frames drawn while `steps` run. */
  const drawnBy = async (steps) => {
    const before = await frames();
    await steps();
    const after = await frames();
    return Object.fromEntries(METHODS.map((m) => [m, after[m] - before[m]]));
  };
  const together = () => page.evaluate(() => window.shadelab.panels.map((p) => !!p.last.together));
  assert.deepEqual(
    await drawnBy(async () => {
      for (let i = 1; i <= 4; i++) await update(page, `s.camera.yaw = ${20 + 7 * i}`);
    }),
    { flat: 12, gouraud: 0, phong: 0 },
    "the first panel's worker drew the three methods of each frame",
  );
  assert.deepEqual(await together(), [true, true, true]);
  const shared = await digests(page);
  const stats = await page.evaluate(() => window.shadelab.panels.map((p) => p.last.stats));
  const costs = () => page.evaluate(() => window.shadelab.panels.map((p) => p.last.cost));
  const cost = await costs();
  // As on two cores (the default there): two workers, each half the rows of
  // the three; the same pictures and counts, the halves' pixels added up.
  await page.evaluate(() => window.shadelab.drawTogether(true, 2));
  await settle(page);
  assert.deepEqual(
    await drawnBy(async () => {
      for (let i = 5; i <= 8; i++) await update(page, `s.camera.yaw = ${20 + 7 * i}`);
      await update(page, 's.camera.yaw = 48');
    }),
    { flat: 15, gouraud: 15, phong: 0 },
    'the first two panels\' workers each drew part of the three methods of each frame',
  );
  assert.deepEqual(await together(), [true, true, true]);
  assert.deepEqual(await digests(page), shared);
  assert.deepEqual(await page.evaluate(() => window.shadelab.panels.map((p) => p.last.stats)), stats);
  assert.deepEqual(await costs(), cost);
  // The scanline rasterizer draws whole frames: in halves, the first
  // worker draws them alone, and the pictures are those drawn as on one core.
  await update(page, "s.rasterizer = 'scanline'");
  await page.evaluate(() => window.shadelab.drawTogether(true, 1));
  await settle(page);
  const scanline = await digests(page);
  await page.evaluate(() => window.shadelab.drawTogether(true, 2));
  await settle(page);
  assert.deepEqual(
    await drawnBy(() => update(page, 's.camera.yaw = 48; s.camera.pitch = 16')),
    { flat: 3, gouraud: 0, phong: 0 },
    'in halves, the scanline frames are drawn by the first worker alone',
  );
  await update(page, 's.camera.pitch = 15');
  assert.deepEqual(await digests(page), scanline);
  await update(page, "s.rasterizer = 'tiled'");
  assert.deepEqual(await digests(page), shared);
  // The Cost tab compares the methods' times: the panels are drawn apart, and
  // the pictures and counts are the same.
  await page.evaluate(() => window.shadelab.setTab('cost'));
  await settle(page);
  assert.deepEqual(await together(), [false, false, false]);
  assert.deepEqual(await digests(page), shared);
  assert.deepEqual(await page.evaluate(() => window.shadelab.panels.map((p) => p.last.stats)), stats);
  // So with an overlay on one panel, and together again once it is gone.
  await page.evaluate(() => window.shadelab.setTab('about'));
  await settle(page);
  assert.deepEqual(await together(), [true, true, true]);
  await update(page, "s.overlays.gouraud = ['wireframe']");
  assert.deepEqual(await together(), [false, false, false]);
  const withOverlay = await digests(page);
  assert.equal(withOverlay.flat, shared.flat);
  assert.notEqual(withOverlay.gouraud, shared.gouraud);
  await update(page, 's.overlays.gouraud = []');
  assert.deepEqual(await together(), [true, true, true]);
  assert.deepEqual(await digests(page), shared);
  // With three cores or more, each worker draws its own panel: the same pictures.
  await page.evaluate(() => window.shadelab.drawTogether(false));
  await settle(page);
  assert.deepEqual(await together(), [false, false, false]);
  assert.deepEqual(await digests(page), shared);
  assert.deepEqual(problems, []);
  await page.close();
});

/** Per-panel render times of `frames` frames, turning the camera, after `warmup` frames. */
async function measure(page, frames, warmup, step) {
  for (let i = 0; i < warmup; i++) await update(page, `s.camera.yaw = ${i * step}`);
  await page.evaluate(() => window.shadelab.panels.forEach((p) => (p.times.length = 0)));
  for (let i = 0; i < frames; i++) await update(page, `s.camera.yaw = ${(warmup + i) * step}`);
  const times = await page.evaluate(() => window.shadelab.frameTimes());
  const out = {};
  for (const m of METHODS) {
    assert.equal(times[m].length, frames);
    out[m] = { median: median(times[m]), p90: percentile(times[m], 0.9), min: Math.min(...times[m]) };
  }
  return out;
}

test('after load the first view is drawn three more times, and the captions start from the last of them', async () => {
  const { page, problems } = await openViewer();
  const seen = () => page.evaluate(() => window.shadelab.panels.map((p) => ({
    method: p.method,
    frames: p.frames,
    times: p.times.length,
    settling: !!p.last.settling,
    label: p.figure.querySelector('.time-label').textContent,
  })));
  // The browser compiles the engine during its first frames: the page draws
  // the first view again while nothing else is asked for (main.js,
  // SETTLING_FRAMES), and each of those frames restarts the captions' times.
  for (const p of await seen()) {
    assert.equal(p.frames, 4, `${p.method}: the first view and three more`);
    assert.equal(p.times, 1, `${p.method}: the caption times the last of them alone`);
    assert.ok(p.settling, p.method);
    assert.match(p.label, /last frame$/, p.method);
  }
  // A change ends them: one frame per key, and the times go on from there.
  await page.locator('.panel[data-method="phong"] canvas').focus();
  await page.keyboard.press('ArrowRight');
  await settle(page);
  for (const p of await seen()) {
    assert.equal(p.frames, 5, `${p.method}: one frame for the key`);
    assert.equal(p.times, 2, p.method);
    assert.ok(!p.settling, p.method);
  }
  assert.deepEqual(problems, []);
  await page.close();
});

test('a quick frame leaves the page alone while it is drawn; a slow one dims its caption', async () => {
  const { page, problems } = await openViewer();
  await settle(page);
  // Orbit steps: the panels' figures change no class while the workers draw
  // (a class change would restyle and repaint the page on the workers' cores).
  const changes = await page.evaluate(async () => {
    const figures = window.shadelab.panels.map((p) => p.figure);
    const seen = [];
    const observer = new MutationObserver((records) => seen.push(...records.map((r) => r.target.className)));
    for (const f of figures) observer.observe(f, { attributes: true, attributeFilter: ['class'] });
    const canvas = figures[0].querySelector('canvas');
    for (let k = 0; k < 5; k++) {
      canvas.dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowRight', bubbles: true, cancelable: true }));
      await window.shadelab.idle();
    }
    await new Promise((r) => setTimeout(r, 300));
    observer.disconnect();
    return seen;
  });
  assert.deepEqual(changes, []);
  // A frame still drawn after 150 ms dims the caption until it is done.
  const dimmed = await page.evaluate(async () => {
    const p = window.shadelab.panels[0];
    const has = () => p.figure.classList.contains('busy');
    p.drawing = true;
    p.showBusySoon();
    const soon = has();
    await new Promise((r) => setTimeout(r, 300));
    const later = has();
    p.drawing = false;
    p.resume();
    return { soon, later, done: has() };
  });
  assert.deepEqual(dimmed, { soon: false, later: true, done: false });
  assert.deepEqual(problems, []);
  await page.close();
});

test('frame times: the default scene re-renders each panel within 16 ms', async () => {
  const { page, problems } = await openViewer();
  // The time is the engine's, measured in each worker around the call. Other
  // processes only ever add to it: on a busy machine, measure up to three
  // times and keep the best run (by its slowest panel's median).
  const runs = [];
  for (let run = 0; run < 3; run++) {
    runs.push(await measure(page, 60, 20, 3));
    if (METHODS.every((m) => runs.at(-1)[m].median <= 16)) break;
  }
  const worst = (r) => Math.max(...METHODS.map((m) => r[m].median));
  const best = runs.reduce((a, b) => (worst(b) < worst(a) ? b : a));
  let bunny = null;
  if (BUNNY) {
    await page.locator('input[type="file"]').setInputFiles(BUNNY);
    await page.waitForFunction(() => window.shadelab.state.model === 'stanford-bunny.obj', null, { timeout: 60000 });
    await settle(page);
    // While the workers draw, the page's own thread stays free: record the
    // gaps between animation frames.
    await page.evaluate(() => {
      window.gaps = [];
      let last = performance.now();
      const tick = (now) => {
        window.gaps.push(now - last);
        last = now;
        if (window.gaps.length < 100000) window.rafId = requestAnimationFrame(tick);
      };
      window.rafId = requestAnimationFrame(tick);
    });
    bunny = await measure(page, 20, 5, 5);
    const gaps = await page.evaluate(() => {
      cancelAnimationFrame(window.rafId);
      return window.gaps.slice(1);
    });
    bunny.pageFrameGap = { median: median(gaps), p90: percentile(gaps, 0.9), max: Math.max(...gaps) };
    await page.screenshot({ path: path.join(ARTIFACTS, 'bunny.png') });
  }
  const all = {
    default: { scene: 'default (teapot), three 480×480 panels', frames: 60, best, runs },
    bunny: bunny && { scene: 'stanford-bunny.obj (69,451 triangles), three 480×480 panels', frames: 20, panels: bunny },
    browser: await page.evaluate(() => navigator.userAgent),
    cpu: os.cpus()[0]?.model,
    cores: os.cpus().length,
    loadavg: os.loadavg(),
  };
  fs.writeFileSync(path.join(ARTIFACTS, 'frame-times.json'), JSON.stringify(all, null, 2));
  console.log(JSON.stringify(all, null, 2));
  for (const m of METHODS) assert.ok(best[m].median <= 16, `${m}: median ${best[m].median} ms`);
  if (bunny) {
    // Interactive: a new picture several times a second even on a busy
    // machine, and the page itself never stalls behind the renderers.
    for (const m of METHODS) assert.ok(bunny[m].median <= 500, `bunny ${m}: median ${bunny[m].median} ms`);
    assert.ok(bunny.pageFrameGap.median <= 50, `the page's frames: ${JSON.stringify(bunny.pageFrameGap)}`);
  }
  assert.deepEqual(problems, []);
  await page.close();
});
