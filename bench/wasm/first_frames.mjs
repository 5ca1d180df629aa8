// The first frames of a mesh as a panel worker draws them, one by one: the
// first builds the mesh's caches, the second a large mesh's copy in a spatial
// order (crates/shadelab-core/src/frame/spatial.rs), the rest are steady.
//   node bench/wasm/first_frames.mjs MODULE.wasm MODEL.obj PART FRAMES
//   node --no-liftoff bench/wasm/first_frames.mjs ...   (no baseline tier: the work, not V8's tier-up)
// (PART of 2; the page's default scene, scene.mjs, the camera turned 5° a
// frame, as part.mjs.) Prints the load time and each frame's ms, as the
// engine reports it and as timed around the call.
import fs from 'node:fs';
import path from 'node:path';
import { Shadelab } from '../../web/js/shadelab.js';
import { SCENE } from './scene.mjs';

const [wasm, model, part, frames] = process.argv.slice(2);
const engine = await Shadelab.create(new WebAssembly.Module(fs.readFileSync(wasm)));
const source = path.basename(model);
let start = performance.now();
engine.loadFile(source, fs.readFileSync(model));
const load = performance.now() - start;
const scene = SCENE.replace('source = "teapot"', `source = ${JSON.stringify(source)}`);
const times = [];
for (let i = 0; i < Number(frames); i++) {
  const yawed = scene.replace('yaw = 0.0', `yaw = ${(i * 5) % 360}.0`);
  start = performance.now();
  const ms = engine.renderMethods(yawed, [], [Number(part), 2]).ms;
  times.push(`${ms.toFixed(1)}/${(performance.now() - start).toFixed(1)}`);
}
console.log(`${source}, part ${part} of 2: loaded in ${load.toFixed(1)} ms; frames (engine/call ms): ${times.join(' ')}`);
