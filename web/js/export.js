// Saving what the page shows: the three panels as one PNG (laid out as
// `shadelab compare` lays them out: a label band above, 4-pixel gaps), and
// the scene file that `shadelab compare` turns into the same three panels.
import { t } from './i18n.js';
import { sceneToml } from './state.js';

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

/** The three panels side by side, labelled, as a canvas. */
export function composePanels(panels) {
  const w = Math.max(...panels.map((p) => p.canvas.width));
  const h = Math.max(...panels.map((p) => p.canvas.height));
  const sheet = document.createElement('canvas');
  sheet.width = panels.length * w + (panels.length - 1) * GAP;
  sheet.height = LABEL_BAND + h;
  const g = sheet.getContext('2d');
  g.fillStyle = 'rgb(32, 32, 40)';
  g.fillRect(0, 0, sheet.width, sheet.height);
  g.font = 'bold 18px system-ui, sans-serif';
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  panels.forEach((p, k) => {
    const x = k * (w + GAP);
    g.drawImage(p.canvas, x, LABEL_BAND);
    g.fillStyle = 'rgb(240, 240, 240)';
    g.fillText(t(`panel.${p.method}`), x + w / 2, LABEL_BAND / 2 + 1);
  });
  return sheet;
}

export function exportPng(panels) {
  composePanels(panels).toBlob((blob) => download(blob, 'shadelab-flat-gouraud-phong.png'), 'image/png');
}

export function exportScene(state, userFile) {
  const header = ['# shadelab scene, saved by the viewer.', '# `shadelab compare scene.toml -o three.png` draws the three panels; `shadelab render` one method (--shading).'];
  if (userFile && state.model === userFile.name) header.push(`# model.source names your file ${userFile.name}: keep it beside this scene file.`);
  const text = `${header.join('\n')}\n\n${sceneToml(state)}`;
  download(new Blob([text], { type: 'text/plain' }), 'scene.toml');
}
