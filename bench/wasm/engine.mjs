// Times the viewer's own engine (crates/shadelab-wasm, through web/js/shadelab.js) under Node:
//   node bench/wasm/engine.mjs MODULE.wasm [teapot|FILE.obj]...
// MODULE.wasm is the viewer's module (target/viewer-wasm/wasm32-unknown-unknown/wasm/shadelab_wasm.wasm,
// built by `cargo build --release`). Each method draws the page's default scene (480×480), the
// camera turned 5° a frame as an orbit step turns it, 3 frames of warm-up, median of FRAMES (30);
// then the three methods in one call (`renderMethods`, as the page draws panels that share a scene),
// and each half of their rows in an engine of its own (as two workers draw them on two cores).
// PAUSE=ms waits that long before each frame, as a user's keys do between orbit steps: the
// machine's caches lose the engine's data meanwhile, and the frame pays to read it again
// (BENCHMARKS.md, "The viewer's latency": a frame after 250 ms idle costs about 1.5× one
// drawn right after the last).
import fs from 'node:fs';
import path from 'node:path';
import { Shadelab } from '../../web/js/shadelab.js';
import { SCENE } from './scene.mjs';

const [wasm, ...models] = process.argv.slice(2);
const module = new WebAssembly.Module(fs.readFileSync(wasm));
const frames = Number(process.env.FRAMES ?? 30);
const pauseMs = Number(process.env.PAUSE ?? 0);
const pause = () => (pauseMs > 0 ? new Promise((resolve) => setTimeout(resolve, pauseMs)) : null);
for (const model of models.length ? models : ['teapot']) {
  const engine = await Shadelab.create(module);
  let source = 'teapot';
  if (model !== 'teapot') {
    source = path.basename(model);
    engine.loadFile(source, fs.readFileSync(model));
  }
  const row = [];
  for (const method of ['flat', 'gouraud', 'phong']) {
    const scene = SCENE.replace('source = "teapot"', `source = ${JSON.stringify(source)}`).replace('shading = "flat"', `shading = "${method}"`);
    const times = [];
    for (let i = 0; i < frames + 3; i++) {
      await pause();
      const frame = engine.render(scene.replace('yaw = 0.0', `yaw = ${(i * 5) % 360}.0`));
      if (i >= 3) times.push(frame.ms);
    }
    times.sort((a, b) => a - b);
    row.push(`${method} ${times[times.length >> 1].toFixed(2)} ms`);
  }
  // The three panels as the page draws them when they share the scene: one call.
  if (engine.renderMethods) {
    const scene = SCENE.replace('source = "teapot"', `source = ${JSON.stringify(source)}`);
    const times = [];
    for (let i = 0; i < frames + 3; i++) {
      await pause();
      const { ms } = engine.renderMethods(scene.replace('yaw = 0.0', `yaw = ${(i * 5) % 360}.0`));
      if (i >= 3) times.push(ms);
    }
    times.sort((a, b) => a - b);
    row.push(`three at once ${times[times.length >> 1].toFixed(2)} ms`);
    // As the page draws them on two cores: each half of the rows by an engine of its own.
    const halves = [];
    for (const part of [0, 1]) {
      const half = await Shadelab.create(module);
      if (model !== 'teapot') half.loadFile(source, fs.readFileSync(model));
      const times = [];
      for (let i = 0; i < frames + 3; i++) {
        await pause();
        const { ms } = half.renderMethods(scene.replace('yaw = 0.0', `yaw = ${(i * 5) % 360}.0`), [], [part, 2]);
        if (i >= 3) times.push(ms);
      }
      times.sort((a, b) => a - b);
      halves.push(times[times.length >> 1].toFixed(2));
    }
    row.push(`halves ${halves.join(' + ')} ms`);
  }
  console.log(source.padEnd(20), row.join('  '));
}
