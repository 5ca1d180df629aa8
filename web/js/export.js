// Saving what the page shows: the three panels as one PNG (laid out as
// `shadelab compare` lays them out: a label band above, 4-pixel gaps), one
// full orbit of them as an animated PNG (as `shadelab compare --orbit`
// makes it), and the scene file that `shadelab compare` turns into the same
// three panels.
import { t } from './i18n.js';
import { sceneToml } from './state.js';
import { ApngWriter } from './apng.js';

const LABEL_BAND = 28;
const GAP = 4;

function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/**
 * Pictures side by side, labelled, as a canvas: `pictures` are
 * [{method, canvas}] or [{method, image: {width, height, pixels}}].
 */
export function composePanels(pictures) {
  const sizes = pictures.map((p) => p.canvas ?? p.image);
  const w = Math.max(...sizes.map((c) => c.width));
  const h = Math.max(...sizes.map((c) => c.height));
  const sheet = document.createElement('canvas');
  sheet.width = pictures.length * w + (pictures.length - 1) * GAP;
  sheet.height = LABEL_BAND + h;
  const g = sheet.getContext('2d', { willReadFrequently: true });
  g.fillStyle = 'rgb(32, 32, 40)';
  g.fillRect(0, 0, sheet.width, sheet.height);
  g.font = 'bold 18px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  pictures.forEach((p, k) => {
    const x = k * (w + GAP);
    if (p.canvas) g.drawImage(p.canvas, x, LABEL_BAND);
    else g.putImageData(new ImageData(p.image.pixels, p.image.width, p.image.height), x, LABEL_BAND);
    g.fillStyle = 'rgb(240, 240, 240)';
    g.fillText(t(`panel.${p.method}`), x + w / 2, LABEL_BAND / 2 + 1);
  });
  return sheet;
}

export function exportPng(panels) {
  composePanels(panels).toBlob((blob) => download(blob, 'shadelab-flat-gouraud-phong.png'), 'image/png');
}

/**
 * One full orbit of the camera, `state.animation.frames` frames shown
 * `state.animation.delay` ms each, the three panels side by side and
 * labelled in each, as an animated PNG. Each frame is drawn by the panels'
 * own workers (the panels keep their pictures); `progress(k, n)` is told of
 * each frame. Resolves to {frames, width, height, bytes}.
 */
export async function exportAnimation(state, panels, progress = () => {}) {
  const { frames: n, delay } = state.animation;
  let writer = null;
  for (let k = 0; k < n; k++) {
    const turned = { ...state, camera: { ...state.camera, yaw: state.camera.yaw + (360 * k) / n } };
    const images = await Promise.all(panels.map((p) => p.ask({ type: 'render', scene: sceneToml(turned, p.method), overlays: state.overlays[p.method].join(',') })));
    const sheet = composePanels(panels.map((p, i) => ({ method: p.method, image: images[i] })));
    writer ??= new ApngWriter(sheet.width, sheet.height, n, delay);
    await writer.add(sheet.getContext('2d').getImageData(0, 0, sheet.width, sheet.height).data);
    progress(k + 1, n);
  }
  const blob = writer.blob();
  download(blob, 'shadelab-orbit.apng');
  return { frames: n, width: writer.width, height: writer.height, bytes: blob.size };
}

let saving = null;
/**
 * Saves one orbit of the page's three panels as an animated PNG
 * ([`exportAnimation`]), with `button` disabled and the progress in the
 * status line meanwhile; resolves to what was saved, or null (the error
 * shown). A second call while saving resolves to the first one's result.
 */
export function saveAnimation(page, button) {
  if (saving) return saving;
  button.disabled = true;
  saving = (async () => {
    try {
      const saved = await exportAnimation(page.state(), page.panels, (k, n) => page.setStatus(t('animation.progress', { k, n })));
      page.setStatus(t('animation.saved', { frames: saved.frames, width: saved.width, height: saved.height }));
      return saved;
    } catch (error) {
      page.setStatus('');
      page.showMessage(t('error.animation', { message: error.message }));
      return null;
    } finally {
      button.disabled = false;
      saving = null;
      // The workers drew the orbit: draw the panels as they were.
      page.rerender();
    }
  })();
  return saving;
}

export function exportScene(state, userFile) {
  const header = ['# shadelab scene, saved by the viewer.', '# `shadelab compare scene.toml -o three.png` draws the three panels; `shadelab render` one method (--shading).'];
  if (userFile && state.model === userFile.name) header.push(`# model.source names your file ${userFile.name}: keep it beside this scene file.`);
  const text = `${header.join('\n')}\n\n${sceneToml(state)}`;
  download(new Blob([text], { type: 'text/plain' }), 'scene.toml');
}
