// A digest of the images the viewer's engine draws, to tell whether two builds
// of the module draw the same pixels (an experiment meant to change no pixel):
//   node bench/wasm/digest.mjs MODULE.wasm [MODEL.obj | teapot]...
// Per model (default: the teapot): the three methods at once (scene.mjs, the
// page's default scene) in both parts of 2, at four yaws, each as it is, with
// screen-space interpolation, and with back faces drawn and the camera close;
// one SHA-256 over all the images' RGBA bytes, printed per model.
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import { Shadelab } from '../../web/js/shadelab.js';
import { SCENE } from './scene.mjs';

const [wasm, ...args] = process.argv.slice(2);
if (!wasm) {
  console.error('usage: node bench/wasm/digest.mjs MODULE.wasm [MODEL.obj | teapot]...');
  process.exit(2);
}
const engine = await Shadelab.create(new WebAssembly.Module(fs.readFileSync(wasm)));
const VARIANTS = [
  (text) => text,
  (text) => text.replace('interpolation = "perspective"', 'interpolation = "screen"'),
  (text) => text.replace('cull_backfaces = true', 'cull_backfaces = false').replace('zoom = 1.0', 'zoom = 2.5'),
];
for (const model of args.length ? args : ['teapot']) {
  let scene = SCENE;
  if (model !== 'teapot') {
    const source = path.basename(model);
    engine.loadFile(source, fs.readFileSync(model));
    scene = SCENE.replace('source = "teapot"', `source = ${JSON.stringify(source)}`);
  }
  const hash = crypto.createHash('sha256');
  let images = 0;
  for (const yaw of [0, 37, 123, 250]) {
    for (const variant of VARIANTS) {
      const text = variant(scene.replace('yaw = 0.0', `yaw = ${yaw}.0`));
      for (const part of [0, 1]) {
        for (const frame of engine.renderMethods(text, [], [part, 2]).frames) {
          hash.update(frame.pixels);
          images += 1;
        }
      }
    }
  }
  console.log(`${hash.digest('hex')}  ${path.basename(model)} (${images} images)`);
}
