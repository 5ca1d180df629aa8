// Moving the camera and the light with the pointer, the wheel, two fingers
// and the keyboard, on any of the three panels (all three share one camera).
import { ZOOM_MIN, ZOOM_MAX } from './state.js';

const DEGREES_PER_PIXEL = 0.5;
const KEY_STEP = 5;

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

/**
 * Wires `canvases` to `state`; `changed()` re-renders; `dragMode()` is
 * 'camera' or 'light' (Shift swaps it while held).
 */
export function attachInteraction(canvases, state, changed, dragMode, resetCamera) {
  const pointers = new Map();
  let pinch = null;
  let mode = 'camera';

  const move = (what, dx, dy) => {
    if (what === 'light') {
      state.light.position = turnLight(state.light.position, dx * DEGREES_PER_PIXEL, -dy * DEGREES_PER_PIXEL);
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
      pointers.set(e.pointerId, { x: e.clientX, y: e.clientY });
      const wanted = dragMode();
      mode = e.shiftKey ? (wanted === 'light' ? 'camera' : 'light') : wanted;
      if (pointers.size === 2) {
        const [a, b] = [...pointers.values()];
        pinch = { distance: Math.hypot(a.x - b.x, a.y - b.y), zoom: state.camera.zoom };
      }
      e.preventDefault();
    });
    canvas.addEventListener('pointermove', (e) => {
      const last = pointers.get(e.pointerId);
      if (!last) return;
      const now = { x: e.clientX, y: e.clientY };
      pointers.set(e.pointerId, now);
      if (pointers.size >= 2 && pinch) {
        const [a, b] = [...pointers.values()];
        const distance = Math.hypot(a.x - b.x, a.y - b.y);
        if (pinch.distance > 0) {
          state.camera.zoom = Number(clampZoom((pinch.zoom * distance) / pinch.distance).toFixed(3));
          changed('zoom');
        }
        return;
      }
      move(mode, now.x - last.x, now.y - last.y);
    });
    const release = (e) => {
      pointers.delete(e.pointerId);
      if (pointers.size < 2) pinch = null;
    };
    canvas.addEventListener('pointerup', release);
    canvas.addEventListener('pointercancel', release);
    canvas.addEventListener(
      'wheel',
      (e) => {
        e.preventDefault();
        const scale = e.deltaMode === 1 ? 40 : e.deltaMode === 2 ? 800 : 1;
        state.camera.zoom = Number(clampZoom(state.camera.zoom * Math.exp(-e.deltaY * scale * 0.0015)).toFixed(3));
        changed('zoom');
      },
      { passive: false },
    );
    canvas.addEventListener('keydown', (e) => {
      const step = e.shiftKey ? 'light' : 'camera';
      const px = KEY_STEP / DEGREES_PER_PIXEL;
      // An arrow does what a drag in its direction does.
      const arrows = { ArrowLeft: [-px, 0], ArrowRight: [px, 0], ArrowUp: [0, -px], ArrowDown: [0, px] };
      if (e.key in arrows) {
        const [dx, dy] = arrows[e.key];
        move(step, dx, dy);
      } else if (e.key === '+' || e.key === '=') {
        state.camera.zoom = Number(clampZoom(state.camera.zoom * 1.1).toFixed(3));
        changed('zoom');
      } else if (e.key === '-' || e.key === '_') {
        state.camera.zoom = Number(clampZoom(state.camera.zoom / 1.1).toFixed(3));
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
