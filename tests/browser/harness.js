// What the browser tests share: the real `shadelab view` server on a free
// port, one headless Chromium (Debian's package, driven by playwright-core),
// and helpers that open the viewer, wait for its frames and read its pixels.
// A test file calls `useViewer()` once, at its top.
import { before, after } from 'node:test';
import { spawn, execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

export const HERE = path.dirname(fileURLToPath(import.meta.url));
export const ROOT = path.resolve(HERE, '../..');
export const BIN = process.env.SHADELAB_BIN ?? path.join(ROOT, 'target/release/shadelab');
export const ARTIFACTS = path.join(HERE, 'artifacts');
export const BUNNY = [path.join(ROOT, '../shared/models/stanford-bunny.obj'), '/work/shared/models/stanford-bunny.obj'].find((p) => fs.existsSync(p));
export const METHODS = ['flat', 'gouraud', 'phong'];

let server;
export let baseUrl;
export let context;
let userDataDir;

/** Starts the server and the browser before this file's tests, stops them after. */
export function useViewer() {
  before(async () => {
    fs.mkdirSync(ARTIFACTS, { recursive: true });
    server = spawn(BIN, ['view', '--port', '0', '--no-open'], { stdio: ['ignore', 'pipe', 'inherit'] });
    baseUrl = await new Promise((resolve, reject) => {
      let out = '';
      server.stdout.on('data', (chunk) => {
        out += chunk;
        const m = /shadelab viewer: (http:\/\/\S+)/.exec(out);
        if (m) resolve(m[1]);
      });
      server.on('exit', (code) => reject(new Error(`shadelab view exited with ${code}: ${out}`)));
    });
    userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-chromium-'));
    context = await chromium.launchPersistentContext(userDataDir, {
      executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
      headless: true,
      acceptDownloads: true,
      viewport: { width: 1600, height: 1000 },
      args: LAUNCH_ARGS,
    });
    await withTestHooks(context);
  });

  after(async () => {
    await context?.close();
    server?.kill();
    if (userDataDir) fs.rmSync(userDataDir, { recursive: true, force: true });
  });
}

/**
 * Gives the pages of `ctx` the viewer's test hooks (`window.shadelab`),
 * which a page has only when this flag is set before its scripts run.
 */
export async function withTestHooks(ctx) {
  await ctx.addInitScript(() => {
    globalThis.SHADELAB_TEST_HOOKS = true;
  });
  return ctx;
}

const LAUNCH_ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

/**
 * A second browser context with its own fresh profile, for options the
 * shared one cannot change (a device pixel ratio): `options` are
 * playwright's (viewport, deviceScaleFactor); `hooks: false` leaves its
 * pages without the test hooks, as a user's. Close it with `.close()`.
 */
export async function otherContext(options, { hooks = true } = {}) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'shadelab-chromium-'));
  const other = await chromium.launchPersistentContext(dir, {
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    acceptDownloads: true,
    args: LAUNCH_ARGS,
    ...options,
  });
  if (hooks) await withTestHooks(other);
  const close = other.close.bind(other);
  other.close = async () => {
    await close();
    fs.rmSync(dir, { recursive: true, force: true });
  };
  return other;
}

/** Opens the viewer (with `hash`), waits for three frames; returns the page and its problems. */
export async function openViewer(hash = '', viewport, inContext = context) {
  const page = await inContext.newPage();
  if (viewport) await page.setViewportSize(viewport);
  const problems = [];
  page.on('console', (m) => {
    if (m.type() === 'error' || m.type() === 'warning') problems.push(`console ${m.type()}: ${m.text()}`);
  });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()} ${r.failure()?.errorText}`));
  page.on('request', (r) => {
    const u = new URL(r.url());
    if (!['blob:', 'data:'].includes(u.protocol) && u.host !== new URL(baseUrl).host) problems.push(`request left the server: ${r.url()}`);
  });
  await page.goto(baseUrl + hash);
  await page.waitForFunction(() => window.shadelab?.panels.every((p) => p.frames > 0), null, { timeout: 60000 });
  await settle(page);
  return { page, problems };
}

/** Waits until no panel has a frame being drawn or waiting. */
export async function settle(page) {
  await page.evaluate(() => new Promise((r) => setTimeout(r, 200)));
  await page.evaluate(() => window.shadelab.idle());
}

/** Waits for the panels and then the open instrument. */
export async function quiet(page) {
  await settle(page);
  await page.evaluate(() => window.shadelab.instrumentsIdle());
}

/** Changes the state as a control would, and waits for the three frames. */
export async function update(page, body) {
  await page.evaluate(`window.shadelab.update((s) => { ${body} })`);
  await settle(page);
}

/** SHA-256 of each panel's pixels. */
export async function digests(page) {
  return page.evaluate(async () => {
    const out = {};
    for (const p of window.shadelab.panels) {
      const data = p.context.getImageData(0, 0, p.canvas.width, p.canvas.height).data;
      const hash = await crypto.subtle.digest('SHA-256', data);
      out[p.method] = [...new Uint8Array(hash)].map((b) => b.toString(16).padStart(2, '0')).join('');
    }
    return out;
  });
}

/** Per panel: covered pixels (not background), distinct colours, highlight pixels, brightest green. */
export async function statistics(page) {
  return page.evaluate(() => {
    const out = {};
    const bg = window.shadelab.state.background;
    for (const p of window.shadelab.panels) {
      const d = p.context.getImageData(0, 0, p.canvas.width, p.canvas.height).data;
      let covered = 0;
      let highlight = 0;
      let maxGreen = 0;
      const colours = new Set();
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] === bg[0] && d[i + 1] === bg[1] && d[i + 2] === bg[2]) continue;
        covered += 1;
        colours.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
        maxGreen = Math.max(maxGreen, d[i + 1]);
        if (d[i + 1] > 150) highlight += 1;
      }
      out[p.method] = { covered, colours: colours.size, highlight, maxGreen };
    }
    return out;
  });
}

/** One panel's RGBA pixels, base64. */
export async function panelPixels(page, method) {
  return page.evaluate((m) => {
    const p = window.shadelab.panels.find((q) => q.method === m);
    const d = p.context.getImageData(0, 0, p.canvas.width, p.canvas.height).data;
    let s = '';
    for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode(...d.subarray(i, i + 0x8000));
    return btoa(s);
  }, method);
}

/** Runs the `shadelab` binary under test with `args`; its standard output. */
export const shadelab = (...args) => execFileSync(BIN, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });

/** A panel's RGBA pixels as a Buffer. */
export const pixelsOf = async (page, method) => Buffer.from(await panelPixels(page, method), 'base64');

/** Polls `condition` in the page until it holds (a loaded machine is slow, never wrong). */
export async function until(page, condition, arg, timeout = 120000) {
  await page.waitForFunction(condition, arg, { timeout, polling: 100 });
}

/** A PNG file's RGBA pixels decoded by the browser, with its size. */
export async function decodePng(page, file) {
  const b64 = fs.readFileSync(file).toString('base64');
  return page.evaluate(async (data) => {
    const bytes = Uint8Array.from(atob(data), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }), { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const g = canvas.getContext('2d');
    g.drawImage(bitmap, 0, 0);
    const d = g.getImageData(0, 0, bitmap.width, bitmap.height).data;
    let s = '';
    for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode(...d.subarray(i, i + 0x8000));
    return { width: bitmap.width, height: bitmap.height, rgba: btoa(s) };
  }, b64);
}

export const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
export const percentile = (xs, q) => [...xs].sort((a, b) => a - b)[Math.min(xs.length - 1, Math.floor(q * xs.length))];

