// One panel's renderer: a Web Worker with its own instance of shadelab's
// WebAssembly. The page posts one message per request and gets one answer
// per request, matched by `id`:
//
//   {type: 'init', module}               -> {type: 'ready', models}
//   {type: 'load-file', id, name, bytes, share}
//                                        -> {type: 'file-loaded', id, summary, mesh?}
//   {type: 'adopt-file', id, name, mesh} -> {type: 'file-adopted', id, summary}
//   {type: 'counts', id}                 -> {type: 'counts', id, counts}
//   {type: 'render', id, scene, overlays, errors, spare?}
//                                        -> {type: 'frame', id, width, height, rasterizer, stats, cost, view, pixels, ms,
//                                            at: {received, posted}, errors?, exact?, bar?}
//   {type: 'render-methods', id, scene, spares?, part?}
//                                        -> {type: 'frames', id, frames: [flat, gouraud, phong], rows, ms, at}
//   {type: 'heat', id, scale, overlays}  -> {type: 'heat', id, scale, pixels}
//   {type: 'inspect', id, scene, x, y, lang}  -> {type: 'inspection', id, inspection}
//   {type: 'profile', id, scene, row | line}  -> {type: 'profile', id, profile}
//   {type: 'quad', id, angle, size, curve}    -> {type: 'quad', id, quad, whole, fans}
//   {type: 'texts', id, lang}            -> {type: 'texts', id, texts}
//   {type: 'cost', id, scene, runs, warmup} -> {type: 'cost', id, times, stats, cost}
//   any request that fails               -> {type: 'error', id, request, message, crashed}
//
// A frame is the scene drawn, then, when asked, its overlays (`overlays`, a
// comma-separated list) or its error map against the exact surface
// (`errors: {scale, exact, bar}`: `pixels` is then the heat map, `exact` the
// exact surface's image). `spare` is the buffer of a frame the page has painted,
// given back to hold this one's pixels. `ms` is the time the engine took to render, measured
// here around that call alone (not the overlays, the error map, the copy of
// the pixels or their way to the page); `at` says when (ms since the epoch) the request
// arrived and the answer left. A new request type is a new case below and a
// new export in crates/shadelab-wasm.
//
// The user's file is parsed by one panel's worker (`load-file` with `share`,
// which answers with the mesh it became as bytes); the others take that mesh
// (`adopt-file`), so a file is parsed once, however many panels draw it.
import { Shadelab, ShadelabError } from './shadelab.js';

/** Milliseconds since the epoch, comparable with the page's (`at` of a frame). */
const now = () => performance.timeOrigin + performance.now();

let module = null;
let engine = null;
/**
 * The user's file as this engine has it, {name, mesh}: the mesh as bytes,
 * taken again (not parsed again) should the instance have to be replaced.
 */
let file = null;

async function restart() {
  engine = await Shadelab.create(module);
  if (file) engine.adoptFile(file.name, file.mesh);
}

const handlers = {
  async init(msg) {
    module = msg.module;
    engine = await Shadelab.create(module);
    return { type: 'ready', models: engine.models() };
  },

  'load-file'(msg) {
    const summary = engine.loadFile(msg.name, msg.bytes);
    file = { name: msg.name, mesh: engine.shareFile() };
    if (!msg.share) return { type: 'file-loaded', summary };
    const mesh = file.mesh.slice();
    return [{ type: 'file-loaded', summary, mesh }, [mesh.buffer]];
  },

  'adopt-file'(msg) {
    const summary = engine.adoptFile(msg.name, msg.mesh);
    file = { name: msg.name, mesh: msg.mesh };
    return { type: 'file-adopted', summary };
  },

  counts() {
    return { type: 'counts', counts: engine.counts() };
  },

  render(msg) {
    const received = now();
    const frame = engine.render(msg.scene, msg.spare);
    const { width, height, rasterizer, stats, cost, view, ms } = frame;
    const reply = { type: 'frame', width, height, rasterizer, stats, cost, view, pixels: frame.pixels, ms, at: { received } };
    if (msg.errors) {
      const answer = engine.errors({ ...msg.errors, overlays: msg.overlays ?? '' });
      const { heat, exact, bar } = answer.images;
      delete answer.images;
      Object.assign(reply, { errors: answer, pixels: heat.pixels, exact, bar });
    } else if (msg.overlays) {
      reply.pixels = engine.overlays(msg.overlays);
    }
    reply.at.posted = now();
    const transfer = [reply.pixels.buffer];
    if (reply.exact) transfer.push(reply.exact.pixels.buffer);
    if (reply.bar) transfer.push(reply.bar.pixels.buffer);
    return [reply, transfer];
  },

  // The three panels' frames in one call, when their texts differ only in
  // the method (no overlays, no error map): the geometry is transformed,
  // set up and binned once. `ms` is the three together. With `part` =
  // [k, n], part k of n of their rows (`rows`, see Shadelab.renderMethods).
  'render-methods'(msg) {
    const received = now();
    const { frames, rows, ms } = engine.renderMethods(msg.scene, msg.spares ?? [], msg.part ?? null);
    const reply = { type: 'frames', frames, rows, ms, at: { received, posted: now() } };
    return [reply, frames.map((f) => f.pixels.buffer)];
  },

  heat(msg) {
    const answer = engine.heat({ scale: msg.scale, overlays: msg.overlays ?? '' });
    const { pixels } = answer.images.heat;
    return [{ type: 'heat', scale: answer.scale, pixels }, [pixels.buffer]];
  },

  inspect(msg) {
    return { type: 'inspection', inspection: engine.inspect({ scene: msg.scene, x: msg.x, y: msg.y, lang: msg.lang }) };
  },

  profile(msg) {
    const request = { scene: msg.scene };
    if (msg.line) request.line = msg.line;
    else request.row = msg.row;
    return { type: 'profile', profile: engine.profile(request) };
  },

  quad(msg) {
    const answer = engine.quad({ angle: msg.angle, size: msg.size, curve: msg.curve ?? [] });
    const { whole, fans } = answer.images;
    delete answer.images;
    return [{ type: 'quad', quad: answer, whole, fans }, [whole.pixels.buffer, fans.pixels.buffer]];
  },

  texts(msg) {
    return { type: 'texts', texts: engine.texts(msg.lang) };
  },

  cost(msg) {
    // Each run timed alone, as a frame is: the median says what a frame costs.
    const times = [];
    let frame = null;
    for (let k = 0; k < (msg.warmup ?? 0); k++) engine.render(msg.scene);
    for (let k = 0; k < Math.max(1, msg.runs); k++) {
      frame = engine.render(msg.scene);
      times.push(frame.ms);
    }
    return { type: 'cost', times, stats: frame.stats, cost: frame.cost, rasterizer: frame.rasterizer };
  },
};

self.onmessage = async (event) => {
  const msg = event.data;
  const handler = handlers[msg.type];
  try {
    if (!handler) throw new ShadelabError(`unknown request ${msg.type}`);
    const answer = await handler(msg);
    const [reply, transfer] = Array.isArray(answer) ? answer : [answer, []];
    self.postMessage({ ...reply, id: msg.id }, transfer);
  } catch (error) {
    // A ShadelabError is the engine refusing the input; anything else (a
    // trap) leaves the instance unusable, so start a fresh one.
    const crashed = !(error instanceof ShadelabError);
    if (crashed && module) {
      try {
        await restart();
      } catch (_) {
        engine = null;
      }
    }
    self.postMessage({ type: 'error', id: msg.id, request: msg.type, message: String(error.message ?? error), crashed });
  }
};
