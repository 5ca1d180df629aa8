// The viewer's latency from input to pixels, measured inside the page in
// headless Chromium: a keydown (one orbit step, ArrowRight) is dispatched on
// a panel's canvas, and the page polls the three canvases until each one's
// pixels have changed. One step is timed at a time, with the panels idle
// before it (after load, default view, three 480×480 panels).
//
//   node run.js [--bin LABEL=PATH]... [--models teapot,bunny,dragon]
//               [--rounds 3] [--steps 20] [--poll busy|light] [--json FILE]
//
// `--parts N` after a `--bin` makes that binary's page draw panels drawn
// together in N parts of their rows, each by its own worker (the page's
// choice otherwise: 2 on two cores or more); a binary may be given twice
// with two labels to compare.
//
// `--poll light` (the default) polls once a millisecond and reads 8 rows
// of each canvas (the whole canvas every 10th round, once 50 ms have
// passed): the event is seen with the page's thread mostly idle, as a
// user's is. The whole canvases are 2.7 MB of `getImageData` at 480²; read
// every 10th round from the start, as until 2026-12-02, they took a core
// from the workers during the frame (the dragon's median 19.1 ms against
// 16.8 without them, in one run; BENCHMARKS.md, "The measure's own reads").
// Only a frame that leaves the canvases' middle rows alone needs them.
// `--poll busy` (the measure as first written) polls in a loop of tasks, reading the three
// canvases whole each time (1.5–5 ms a round on a 2-core machine): it keeps
// one core busy while the workers draw (on two cores, one of the two that
// draw the halves of a frame), and a frame's answer waits for the round in
// progress.
//
// Each `--bin` is a `shadelab` binary (default: this tree's
// target/release/shadelab), started as `shadelab view --port 0 --no-open`;
// `LABEL=web` serves this tree's `web/` and the WebAssembly last built in
// target/viewer-wasm (or the module SHADELAB_WASM names), with the
// params.json that `shadelab view --export` writes (the binary SHADELAB_BIN
// names, else this tree's target/release/shadelab), from a small Node
// server instead, for trying a change to the page without rebuilding the
// binary (`LABEL=web+isolated` adds the COOP/COEP headers). With several binaries the rounds alternate between
// them, model by model, so that the machine's load falls on all alike.
// The bunny and the dragon are read from ../shared/models (never copied).
import { execFileSync, spawn } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const HERE = path.dirname(fileURLToPath(import.meta.url));
const ROOT = path.resolve(HERE, '../..');
const SHARED = [path.join(ROOT, '../shared/models'), '/work/shared/models'].find((p) => fs.existsSync(p));
const MODELS = {
  teapot: { file: null, what: 'teapot (built in, 2,048 quads)' },
  bunny: { file: 'stanford-bunny.obj', what: 'Stanford bunny (69,451 triangles)' },
  dragon: { file: 'dragon_100k.obj', what: 'Asian dragon (100,000 triangles)' },
};
const METHODS = ['flat', 'gouraud', 'phong'];

function parseArgs(argv) {
  const args = { bins: [], models: ['teapot', 'bunny', 'dragon'], rounds: 3, steps: 20, warmup: 5, poll: 'light', json: null };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    const value = () => argv[++i];
    if (a === '--bin') {
      const v = value();
      const eq = v.indexOf('=');
      args.bins.push(eq < 0 ? { label: v, path: v } : { label: v.slice(0, eq), path: v.slice(eq + 1) });
    } else if (a === '--models') args.models = value().split(',');
    else if (a === '--rounds') args.rounds = Number(value());
    else if (a === '--steps') args.steps = Number(value());
    else if (a === '--warmup') args.warmup = Number(value());
    else if (a === '--poll') args.poll = value();
    else if (a === '--json') args.json = value();
    else if (a === '--parts') {
      if (!args.bins.length) throw new Error('--parts follows the --bin it is for');
      args.bins.at(-1).parts = Number(value());
    } else throw new Error(`unknown argument ${a}`);
  }
  if (!args.bins.length) args.bins.push({ label: 'this tree', path: path.join(ROOT, 'target/release/shadelab') });
  for (const m of args.models) if (!MODELS[m]) throw new Error(`unknown model ${m}`);
  return args;
}

/** Starts `shadelab view` (or the Node server of `web/`); resolves to {url, stop}. */
async function startServer(bin) {
  if (bin.path === 'web' || bin.path === 'web+isolated') return startWebServer(bin.path === 'web+isolated');
  const server = spawn(bin.path, ['view', '--port', '0', '--no-open'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = await new Promise((resolve, reject) => {
    let out = '';
    server.stdout.on('data', (chunk) => {
      out += chunk;
      const m = /shadelab viewer: (http:\/\/\S+)/.exec(out);
      if (m) resolve(m[1]);
    });
    server.on('exit', (code) => reject(new Error(`${bin.path} exited with ${code}: ${out}`)));
  });
  return { url, stop: () => server.kill() };
}

function startWebServer(isolated) {
  const web = path.join(ROOT, 'web');
  const wasm = process.env.SHADELAB_WASM ?? path.join(ROOT, 'target/viewer-wasm/wasm32-unknown-unknown/wasm/shadelab_wasm.wasm');
  const types = { html: 'text/html', js: 'text/javascript', css: 'text/css', wasm: 'application/wasm', svg: 'image/svg+xml', json: 'application/json' };
  // The parameters' schema is made by the binary, from the core's table.
  const site = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-site-'));
  execFileSync(process.env.SHADELAB_BIN ?? path.join(ROOT, 'target/release/shadelab'), ['view', '--export', path.join(site, 'x')]);
  const params = path.join(site, 'x/params.json');
  const server = http.createServer((req, res) => {
    const name = new URL(req.url, 'http://x').pathname.replace(/^\/$/, '/index.html');
    const file = name === '/shadelab.wasm' ? wasm : name === '/params.json' ? params : path.join(web, path.normalize(name));
    if (!(file === wasm || file === params || file.startsWith(web)) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) {
      res.writeHead(404).end();
      return;
    }
    const headers = { 'Content-Type': types[path.extname(file).slice(1)] ?? 'application/octet-stream', 'Cache-Control': 'no-cache' };
    if (isolated) Object.assign(headers, { 'Cross-Origin-Opener-Policy': 'same-origin', 'Cross-Origin-Embedder-Policy': 'require-corp' });
    res.writeHead(200, headers);
    res.end(fs.readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({
    url: `http://127.0.0.1:${server.address().port}/`,
    stop: () => server.close(),
  })));
}

/** Opens the viewer with model `name` loaded and drawn; returns the page. */
async function openModel(context, url, name) {
  const page = await context.newPage();
  await page.setViewportSize({ width: 1600, height: 1000 });
  page.on('pageerror', (e) => console.error(`page error: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction(() => window.shadelab?.panels.every((p) => p.frames > 0), null, { timeout: 120000 });
  const file = MODELS[name].file;
  if (file) {
    await page.locator('input[type="file"]').setInputFiles(path.join(SHARED, file));
    await page.waitForFunction((f) => window.shadelab.state.model === f, file, { timeout: 120000 });
  }
  await page.evaluate(() => window.shadelab.idle());
  // The panels' size as a user sees them by default.
  const size = await page.evaluate(() => [...document.querySelectorAll('.panel:not(.exact) canvas')].map((c) => `${c.width}x${c.height}`));
  return { page, size };
}

/**
 * Times `steps` orbit steps inside the page (after `warmup` untimed ones):
 * each, from dispatching the keydown to the poll that sees the third canvas
 * changed. Polls run as tasks of their own (see `--poll`), so the workers'
 * answers are handled between them as they would be anyway.
 */
function measureInPage({ steps, warmup, poll }) {
  const canvases = [...document.querySelectorAll('.panel:not(.exact) canvas')];
  const contexts = canvases.map((c) => c.getContext('2d', { willReadFrequently: true }));
  const channel = new MessageChannel();
  const nextTask = () => new Promise((resolve) => {
    channel.port1.onmessage = () => resolve();
    channel.port2.postMessage(0);
  });
  // `--poll light` waits 1 ms between polls (a timer of the scheduler, which
  // has no 4 ms clamp) and reads only 8 rows across the middle of each
  // canvas, the whole canvas every 10th poll (a change elsewhere is still
  // seen): the page's thread stays mostly idle, as it is for a user.
  const pause = poll === 'light' ? () => scheduler.postTask(() => {}, { delay: 1 }) : nextTask;
  const band = (k) => [Math.max(0, (canvases[k].height >> 1) - 4), Math.min(8, canvases[k].height)];
  const pixels = (k) => new Uint32Array(contexts[k].getImageData(0, 0, canvases[k].width, canvases[k].height).data.buffer);
  const bandPixels = (k) => {
    const [y, rows] = band(k);
    return new Uint32Array(contexts[k].getImageData(0, y, canvases[k].width, rows).data.buffer);
  };
  const bandOf = (k, whole) => {
    const [y, rows] = band(k);
    return whole.subarray(y * canvases[k].width, (y + rows) * canvases[k].width);
  };
  const differs = (a, b) => {
    if (a.length !== b.length) return true;
    for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return true;
    return false;
  };
  // `--poll light` reads whole canvases only for a frame not seen by then.
  const WHOLE_AFTER_MS = 50;
  const changedNow = (k, before, round, start) => {
    const whole = round % 10 === 9 && performance.now() - start > WHOLE_AFTER_MS;
    if (poll !== 'light' || whole) return differs(before, pixels(k));
    return differs(bandOf(k, before), bandPixels(k));
  };
  const rest = () => new Promise((resolve) => setTimeout(resolve, 250));
  return (async () => {
    const times = [];
    const split = [];
    const frameCounts = () => window.shadelab.panels.map((p) => p.times.length);
    let counts = null;
    for (let k = 0; k < warmup + steps; k++) {
      await rest();
      await window.shadelab.idle();
      if (k === warmup) counts = frameCounts();
      const before = canvases.map((_, i) => pixels(i));
      const changed = canvases.map(() => false);
      const start = performance.now();
      canvases[0].dispatchEvent(new KeyboardEvent('keydown', { key: 'ArrowRight', bubbles: true, cancelable: true }));
      for (let round = 0; ; round++) {
        for (let i = 0; i < canvases.length; i++) if (!changed[i]) changed[i] = changedNow(i, before[i], round, start);
        if (changed.every(Boolean)) break;
        if (performance.now() - start > 10000) throw new Error('the panels did not change within 10 s');
        await pause();
      }
      const seen = performance.now();
      if (k >= warmup) {
        times.push(seen - start);
        // Where the last panel's time went, when the page records it (panels.js: `timings`).
        const last = window.shadelab.panels.map((p) => p.timings?.at(-1)).filter(Boolean)
          .sort((a, b) => a.painted - b.painted).at(-1);
        if (last) {
          const origin = performance.timeOrigin;
          const engine = window.shadelab.panels.find((p) => p.timings.at(-1) === last).times.at(-1);
          split.push({
            before: last.sent - (origin + start),
            in: last.received - last.sent,
            engine,
            worker: last.posted - last.received - engine,
            out: last.arrived - last.posted,
            paint: last.painted - last.arrived,
            poll: origin + seen - last.painted,
          });
        }
      }
    }
    // The engine's own time per method for the timed steps, as each worker measured it.
    const render = {};
    window.shadelab.panels.forEach((p, i) => {
      render[p.method] = p.times.slice(counts[i]);
    });
    return { times, render, split };
  })();
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const percentile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(q * xs.length))];
const fmt = (x) => x.toFixed(1);

async function main() {
  const args = parseArgs(process.argv.slice(2));
  if (args.models.some((m) => MODELS[m].file) && !SHARED) throw new Error('../shared/models is missing: use --models teapot');
  const servers = [];
  for (const bin of args.bins) servers.push(await startServer(bin));
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-bench-'));
  const context = await chromium.launchPersistentContext(dir, {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', ...(process.env.CHROMIUM_FLAGS ?? '').split(' ').filter(Boolean)],
  });
  // The page's hooks for tests (frame times, idle) exist only under this flag.
  await context.addInitScript(() => {
    globalThis.SHADELAB_TEST_HOOKS = true;
  });
  const results = [];
  try {
    for (const model of args.models) {
      const rows = args.bins.map((bin) => ({ bin: bin.label, model, times: [], render: { flat: [], gouraud: [], phong: [] }, split: [], load: [] }));
      for (let round = 0; round < args.rounds; round++) {
        for (let b = 0; b < args.bins.length; b++) {
          // Alternate the order each round as well.
          const k = round % 2 ? args.bins.length - 1 - b : b;
          const row = rows[k];
          const { page, size } = await openModel(context, servers[k].url, model);
          if (args.bins[k].parts) {
            await page.evaluate((n) => window.shadelab.drawTogether('auto', n), args.bins[k].parts);
            await page.evaluate(() => window.shadelab.idle());
          }
          row.size = size;
          row.isolated = await page.evaluate(() => globalThis.crossOriginIsolated === true);
          row.load.push(os.loadavg()[0]);
          const r = await page.evaluate(measureInPage, { steps: args.steps, warmup: args.warmup, poll: args.poll });
          row.load.push(os.loadavg()[0]);
          row.times.push(...r.times);
          row.split.push(...r.split);
          for (const m of METHODS) row.render[m].push(...r.render[m]);
          await page.close();
          process.stderr.write(`${model} ${row.bin} round ${round + 1}: median ${fmt(median(r.times))} ms\n`);
        }
      }
      results.push(...rows);
    }
  } finally {
    await context.close();
    for (const s of servers) s.stop();
    fs.rmSync(dir, { recursive: true, force: true });
  }
  const cpu = os.cpus()[0]?.model ?? '?';
  const browser = await chromiumVersion();
  console.log(`\nviewer latency, keydown → all three panels changed (ms), ${args.rounds} rounds × ${args.steps} steps per binary and model, --poll ${args.poll}`);
  console.log(`machine: ${os.cpus().length} × ${cpu}; ${browser}; load average during the runs ${fmt(Math.min(...results.flatMap((r) => r.load)))}–${fmt(Math.max(...results.flatMap((r) => r.load)))}\n`);
  console.log('| model | build | latency median | p90 | render flat | Gouraud | Phong (worker, median) |');
  console.log('|---|---|---:|---:|---:|---:|---:|');
  for (const r of results) {
    const render = METHODS.map((m) => (r.render[m].length ? fmt(median(r.render[m])) : '–'));
    console.log(`| ${r.model} | ${r.bin}${r.isolated ? ' (isolated)' : ''} | ${fmt(median(r.times))} | ${fmt(percentile(r.times, 0.9))} | ${render.join(' | ')} |`);
  }
  const parts = ['before', 'in', 'engine', 'worker', 'out', 'paint', 'poll'];
  const split = results.filter((r) => r.split.length);
  if (split.length) {
    console.log('\nwhere the last panel\'s time goes (ms, medians over the steps): before = keydown to the request posted; in = to the worker;');
    console.log('engine = the WebAssembly call; worker = the rest in the worker (scene text in, pixels out); out = back to the page; paint = putImageData; poll = until the page\'s poll saw it\n');
    console.log(`| model | build | ${parts.join(' | ')} |`);
    console.log(`|---|---|${parts.map(() => '---:').join('|')}|`);
    for (const r of split) console.log(`| ${r.model} | ${r.bin} | ${parts.map((k) => fmt(median(r.split.map((x) => x[k])))).join(' | ')} |`);
  }
  if (args.json) fs.writeFileSync(args.json, JSON.stringify({ cpu, browser, args, results }, null, 2));
}

async function chromiumVersion() {
  return new Promise((resolve) => {
    const p = spawn(process.env.CHROMIUM ?? '/usr/bin/chromium', ['--version'], { stdio: ['ignore', 'pipe', 'ignore'] });
    let out = '';
    p.stdout.on('data', (c) => (out += c));
    p.on('exit', () => resolve(out.trim() || 'Chromium'));
  });
}

main().catch((e) => {
  console.error(e);
  process.exit(1);
});
