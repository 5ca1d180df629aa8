// Times the viewer's workload in WebAssembly and checks the SIMD levels agree:
//   node bench/wasm/run.js FILE.wasm [WxH] [frames] [model...]
// model: teapot (built in) or an OBJ file (e.g. ../shared/models/dragon_100k.obj).
// Each method is drawn with the portable lanes and with the module's best
// level (simd128 when built with it), turning the camera 5° a frame; the two
// images of every frame must have identical coverage and colours within 1/255.
const fs = require("fs");
const path = require("path");
const [file, size = "480x480", count = "30", ...models] = process.argv.slice(2);
const [w, h] = size.split("x").map(Number);
const LEVELS = ["portable", "avx2", "simd128", "avx512"];
const instance = new WebAssembly.Instance(new WebAssembly.Module(fs.readFileSync(file)), {});
const e = instance.exports;
const best = e.level();
let failed = false;
for (const model of models.length ? models : ["teapot"]) {
  if (model === "teapot") {
    if (e.setup(8, w, h) !== 0) throw new Error("setup failed");
  } else {
    const bytes = fs.readFileSync(model);
    const at = e.input(bytes.length); // may grow the memory: take its buffer after
    new Uint8Array(e.memory.buffer, at, bytes.length).set(bytes);
    if (e.load(w, h) !== 0) throw new Error(`${model}: load failed`);
  }
  const name = path.basename(model, ".obj");
  for (const [k, method] of ["flat", "gouraud", "phong"].entries()) {
    const times = [[], []];
    let worst = 0;
    let coverage = 0;
    for (let i = 0; i < 5 + Number(count); i++) {
      const images = [];
      for (const level of [0, 1]) {
        const t = performance.now();
        e.frame(k, level, i * 5);
        if (i >= 5) times[level].push(performance.now() - t);
        images.push(new Uint8Array(e.memory.buffer, e.pixels(), e.pixels_len()).slice());
      }
      for (let p = 0; p < images[0].length; p += 3) {
        const bg = (img) => img[p] === 0 && img[p + 1] === 0 && img[p + 2] === 0;
        if (bg(images[0]) !== bg(images[1])) coverage += 1;
        for (let c = 0; c < 3; c++) worst = Math.max(worst, Math.abs(images[0][p + c] - images[1][p + c]));
      }
    }
    const median = (xs) => [...xs].sort((a, b) => a - b)[xs.length >> 1].toFixed(2);
    if (worst > 1 || coverage > 0) failed = true;
    console.log(`${name.padEnd(14)} ${method.padEnd(8)} ${size}  portable ${median(times[0])} ms  ${LEVELS[best]} ${median(times[1])} ms  largest difference ${worst}/255, coverage differs at ${coverage} px`);
  }
}
if (failed) {
  console.error("the levels disagree");
  process.exit(1);
}
