// One panel's renderer: a Web Worker with its own instance of shadelab's
// WebAssembly. The page posts one message per request and gets one answer
// per request, matched by `id`:
//
//   {type: 'init', module}              -> {type: 'ready', models}
//   {type: 'load-file', id, name, bytes} -> {type: 'file-loaded', id, summary}
//   {type: 'render', id, scene}          -> {type: 'frame', id, width, height, pixels, stats, ms}
//   any request that fails               -> {type: 'error', id, request, message, crashed}
//
// `ms` is the time the engine took, measured here around the call. A new
// request type is a new case below and a new export in crates/shadelab-wasm.
import { Shadelab, ShadelabError } from './shadelab.js';

let module = null;
let engine = null;
/** The last file loaded, loaded again should the instance have to be replaced. */
let file = null;

async function restart() {
  engine = await Shadelab.create(module);
  if (file) engine.loadFile(file.name, file.bytes);
}

const handlers = {
  async init(msg) {
    module = msg.module;
    engine = await Shadelab.create(module);
    return { type: 'ready', models: engine.models() };
  },

  'load-file'(msg) {
    const summary = engine.loadFile(msg.name, msg.bytes);
    file = { name: msg.name, bytes: msg.bytes };
    return { type: 'file-loaded', summary };
  },

  render(msg) {
    const start = performance.now();
    const frame = engine.render(msg.scene);
    const ms = performance.now() - start;
    const { width, height, stats, pixels } = frame;
    return [{ type: 'frame', width, height, stats, pixels, ms }, [pixels.buffer]];
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
