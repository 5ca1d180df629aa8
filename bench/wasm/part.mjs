// One part of the three methods at once, as a panel worker draws it, FRAMES times:
//   node bench/wasm/part.mjs MODULE.wasm MODEL.obj PART FRAMES
// (PART of 2; the page's default scene, scene.mjs, the camera turned 5° a
// frame). Prints the median frame. Run by profile.sh under Node's profiler.
import fs from 'node:fs';
import path from 'node:path';
import { Shadelab } from '../../web/js/shadelab.js';
import { SCENE } from './scene.mjs';

const [wasm, model, part, frames] = process.argv.slice(2);
const engine = await Shadelab.create(new WebAssembly.Module(fs.readFileSync(wasm)));
const source = path.basename(model);
engine.loadFile(source, fs.readFileSync(model));
const scene = SCENE.replace('source = "teapot"', `source = ${JSON.stringify(source)}`);
const times = [];
for (let i = 0; i < Number(frames); i++) {
  const yawed = scene.replace('yaw = 0.0', `yaw = ${(i * 5) % 360}.0`);
  times.push(engine.renderMethods(yawed, [], [Number(part), 2]).ms);
}
times.sort((a, b) => a - b);
console.log(`${source}, part ${part} of 2: median ${times[times.length >> 1].toFixed(2)} ms over ${frames} frames`);
