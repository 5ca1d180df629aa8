// Times the viewer's workload in WebAssembly: node bench/wasm/run.js FILE.wasm [WxH] [frames]
const fs = require("fs");
const [file, size = "480x480", count = "60"] = process.argv.slice(2);
const [w, h] = size.split("x").map(Number);
const instance = new WebAssembly.Instance(new WebAssembly.Module(fs.readFileSync(file)), {});
const e = instance.exports;
if (e.setup(8, w, h) !== 0) throw new Error("setup failed");
for (const [k, name] of ["flat", "gouraud", "phong"].entries()) {
  for (let i = 0; i < 5; i++) e.frame(k);
  const times = [];
  let covered = 0;
  for (let i = 0; i < Number(count); i++) {
    const t = performance.now();
    covered = e.frame(k);
    times.push(performance.now() - t);
  }
  times.sort((a, b) => a - b);
  console.log(`${name.padEnd(8)} ${size}  median ${times[times.length >> 1].toFixed(2)} ms  (min ${times[0].toFixed(2)})  ${covered} px`);
}
