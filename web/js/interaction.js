// Moving the camera and the lights with the pointer, the wheel, two fingers
// and the keyboard, on any of the panels (all share one camera); and picking
// what the instruments look at: a click picks a pixel, Alt+click a row,
// Alt+drag a line. A press that moves less than a few pixels is a click; a
// press on a light's marker drags that light; a double click resets the camera.
// A file dropped on the panels is opened.
import { ZOOM_MIN, ZOOM_MAX } from './state.js';

const DEGREES_PER_PIXEL = 0.5;
const KEY_STEP = 5;
/** One wheel notch (or one + / − key) zooms by this factor: 10 %. */
export const ZOOM_STEP = 1.1;
/** Pixels of wheel movement Chromium and Firefox report for one notch. */
const PIXELS_PER_NOTCH = 100;
/** A press within this many CSS pixels of a light's marker grabs the light. */
const MARKER_REACH = 14;

const clampZoom = (z) => Math.min(ZOOM_MAX, Math.max(ZOOM_MIN, z));
const clampPitch = (p) => Math.min(89, Math.max(-89, p));

/** Turns the light about the model's centre: azimuth about +y, then elevation. */
export function turnLight(position, dAzimuth, dElevation) {
  const [x, y, z] = position;
  const r = Math.hypot(x, y, z);
  if (r === 0) return position;
  const azimuth = Math.atan2(x, z) + (dAzimuth * Math.PI) / 180;
  const limit = (89 * Math.PI) / 180;
  const elevation = Math.min(limit, Math.max(-limit, Math.asin(y / r) + (dElevation * Math.PI) / 180));
  const round = (v) => Number(v.toFixed(3));
  return [
    round(r * Math.cos(elevation) * Math.sin(azimuth)),
    round(r * Math.sin(elevation)),
    round(r * Math.cos(elevation) * Math.cos(azimuth)),
  ];
}

/** A pointer further than this from where it went down (CSS pixels) drags; nearer, it clicks. */
const CLICK_SLOP = 4;

/** The image pixel under a pointer event on `canvas`, clamped to the image. */
export function pixelAt(canvas, e) {
  const r = canvas.getBoundingClientRect();
  const fx = ((e.clientX - r.left) / r.width) * canvas.width;
  const fy = ((e.clientY - r.top) / r.height) * canvas.height;
  return {
    x: Math.min(canvas.width - 1, Math.max(0, Math.floor(fx))),
    y: Math.min(canvas.height - 1, Math.max(0, Math.floor(fy))),
    fx: Math.min(canvas.width, Math.max(0, fx)),
    fy: Math.min(canvas.height, Math.max(0, fy)),
  };
}

/** The zoom after `notches` steps of 10 % (positive: closer), within the limits. */
export function zoomBy(zoom, notches) {
  return Number(clampZoom(zoom * ZOOM_STEP ** notches).toFixed(3));
}

/** The light turned about the model's centre, whichever its kind. */
function turnAnyLight(light, dAzimuth, dElevation) {
  if (light.kind === 'point') return { ...light, position: turnLight(light.position, dAzimuth, dElevation) };
  // A directional light turns as a point light on the side its rays come from would.
  const from = turnLight(light.direction.map((x) => -x), dAzimuth, dElevation);
  return { ...light, direction: from.map((x) => -x) };
}

/**
 * Wires `canvases` to `state`; `changed()` re-renders; `dragMode()` is
 * 'camera' or 'light' (Shift swaps it while held); the light dragged is
 * `lights.active()`. A click (no drag) calls `picks.pixel(x, y)`; with Alt
 * (or Ctrl, or ⌘) `picks.row(y)`, and an Alt+drag draws a line,
 * `picks.preview([x0, y0, x1, y1] | null)` while dragging and
 * `picks.line([x0, y0, x1, y1])` at the end. A press on a light's marker
 * (`lights.at(canvas, x, y, reach)` finds it, in image pixels) drags it:
 * `lights.drag(k, canvas, x, y)` places it under the pointer,
 * `lights.release()` ends the drag.
 */
export function attachInteraction(canvases, state, changed, dragMode, resetCamera, picks, lights) {
  const pointers = new Map();
  let pinch = null;
  let mode = 'camera';
  let grabbed = null;

  const move = (what, dx, dy) => {
    if (what === 'light') {
      const k = lights.active();
      if (!state.lights[k]) return;
      state.lights[k] = turnAnyLight(state.lights[k], dx * DEGREES_PER_PIXEL, -dy * DEGREES_PER_PIXEL);
    } else {
      state.camera.yaw = Number((state.camera.yaw - dx * DEGREES_PER_PIXEL).toFixed(2));
      state.camera.pitch = Number(clampPitch(state.camera.pitch + dy * DEGREES_PER_PIXEL).toFixed(2));
    }
    changed(what);
  };

  for (const canvas of canvases) {
    canvas.addEventListener('pointerdown', (e) => {
      if (e.button !== 0 && e.pointerType === 'mouse') return;
      canvas.setPointerCapture(e.pointerId);
      const at = { x: e.clientX, y: e.clientY };
      const image = pixelAt(canvas, e);
      pointers.set(e.pointerId, { ...at, start: at, dragging: false, image });
      const wanted = dragMode();
      const reach = (MARKER_REACH * canvas.width) / (canvas.getBoundingClientRect().width || 1);
      const marker = e.altKey || e.ctrlKey || e.metaKey ? null : lights.at(canvas, image.fx, image.fy, reach);
      grabbed = null;
      if (marker !== null) {
        mode = 'marker';
        grabbed = marker;
        lights.select(marker);
      } else if (e.altKey || e.ctrlKey || e.metaKey) mode = 'line';
      else mode = e.shiftKey ? (wanted === 'light' ? 'camera' : 'light') : wanted;
      if (pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        pinch = { distance: Math.hypot(a.x - b.x, a.y - b.y), zoom: state.camera.zoom };
      }
      e.preventDefault();
    });
    canvas.addEventListener('pointermove', (e) => {
      const p = pointers.get(e.pointerId);
      if (!p) {
        // Pointing, not pressing: the inspector's magnifiers follow.
        const at = pixelAt(canvas, e);
        picks.hover?.([at.x, at.y]);
        return;
      }
      const now = { x: e.clientX, y: e.clientY };
      if (pointers.size >= 2 && pinch) {
        Object.assign(p, now);
        const [a, b] = [...pointers.values()];
        const distance = Math.hypot(a.x - b.x, a.y - b.y);
        if (pinch.distance > 0) {
          state.camera.zoom = Number(clampZoom((pinch.zoom * distance) / pinch.distance).toFixed(3));
          changed('zoom');
        }
        return;
      }
      if (!p.dragging && Math.hypot(now.x - p.start.x, now.y - p.start.y) <= CLICK_SLOP) return;
      p.dragging = true;
      if (mode === 'marker') {
        const to = pixelAt(canvas, e);
        lights.drag(grabbed, canvas, to.fx, to.fy);
        changed('light');
      } else if (mode === 'line') {
        const end = pixelAt(canvas, e);
        picks.preview([p.image.fx, p.image.fy, end.fx, end.fy]);
      } else {
        // The first move past the slop moves by all of it: a drag loses nothing.
        move(mode, now.x - p.x, now.y - p.y);
      }
      Object.assign(p, now);
    });
    const release = (e, cancelled) => {
      const p = pointers.get(e.pointerId);
      pointers.delete(e.pointerId);
      const wasPinch = pinch !== null;
      if (pointers.size < 2) pinch = null;
      if (mode === 'marker') lights.release();
      if (!p || cancelled || wasPinch) {
        if (mode === 'line') picks.preview(null);
        return;
      }
      if (mode === 'line') {
        picks.preview(null);
        if (p.dragging) {
          const end = pixelAt(canvas, e);
          picks.line([p.image.fx, p.image.fy, end.fx, end.fy].map((v) => Number(v.toFixed(1))));
        } else {
          picks.row(p.image.y);
        }
      } else if (!p.dragging && mode !== 'marker') {
        picks.pixel(p.image.x, p.image.y, canvas);
      }
    };
    canvas.addEventListener('pointerleave', () => picks.hover?.(null));
    canvas.addEventListener('pointerup', (e) => release(e, false));
    canvas.addEventListener('pointercancel', (e) => release(e, true));
    canvas.addEventListener(
      'wheel',
      (e) => {
        e.preventDefault();
        // In notches: lines and pages count as a notch each, pixels as a
        // hundredth (a touchpad's small movements zoom a little).
        const notches = e.deltaMode === 0 ? e.deltaY / PIXELS_PER_NOTCH : Math.sign(e.deltaY);
        state.camera.zoom = zoomBy(state.camera.zoom, -notches);
        changed('zoom');
      },
      { passive: false },
    );
    canvas.addEventListener('dblclick', (e) => {
      e.preventDefault();
      resetCamera();
    });
    canvas.addEventListener('keydown', (e) => {
      const step = e.shiftKey ? 'light' : 'camera';
      const px = KEY_STEP / DEGREES_PER_PIXEL;
      // An arrow does what a drag in its direction does.
      const arrows = { ArrowLeft: [-px, 0], ArrowRight: [px, 0], ArrowUp: [0, -px], ArrowDown: [0, px] };
      if (e.key in arrows) {
        const [dx, dy] = arrows[e.key];
        move(step, dx, dy);
      } else if (e.key === '+' || e.key === '=') {
        state.camera.zoom = zoomBy(state.camera.zoom, 1);
        changed('zoom');
      } else if (e.key === '-' || e.key === '_') {
        state.camera.zoom = zoomBy(state.camera.zoom, -1);
        changed('zoom');
      } else if (e.key === '0' || e.key === 'Home') {
        resetCamera();
      } else {
        return;
      }
      e.preventDefault();
    });
  }
}

/** Opens a file dropped on `zone` with `open(file)`, showing the zone as a target while a file is dragged over it. */
export function attachDrop(zone, open) {
  let depth = 0;
  zone.addEventListener('dragenter', (e) => {
    if (![...e.dataTransfer.types].includes('Files')) return;
    depth += 1;
    zone.classList.add('dragging');
    e.preventDefault();
  });
  zone.addEventListener('dragover', (e) => {
    if ([...e.dataTransfer.types].includes('Files')) e.preventDefault();
  });
  zone.addEventListener('dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (depth === 0) zone.classList.remove('dragging');
  });
  zone.addEventListener('drop', (e) => {
    e.preventDefault();
    depth = 0;
    zone.classList.remove('dragging');
    const file = e.dataTransfer.files[0];
    if (file) open(file);
  });
}
