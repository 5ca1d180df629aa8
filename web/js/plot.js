// Line plots on a 2D canvas, for the profile and the quad study: axes with
// round ticks, curves with gaps where a value is missing, vertical marks
// (polygon edges, a cursor). Drawn at the screen's resolution, with type
// and lines large enough to read on a projected screen.
import { formatNumber } from './i18n.js';

const AXIS = 'rgba(236, 236, 241, 0.55)';
const GRID = 'rgba(236, 236, 241, 0.12)';
const TEXT = '#ececf1';

/** Round tick values covering [lo, hi], about `count` of them. */
export function ticks(lo, hi, count = 5) {
  const span = hi - lo || 1;
  const raw = span / count;
  const p = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? 10 * p;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return { values: out, step };
}

/**
 * Draws a plot into `canvas` (sized by CSS). `spec`: {x: [lo, hi], y: [lo, hi],
 * series: [{points: [[x, y | null]], color, width, dash}], vlines: [{x, color, dash}],
 * xLabel, yLabel, zeroLine}. Returns the mapping from data to CSS pixels.
 */
export function drawPlot(canvas, spec) {
  const dpr = window.devicePixelRatio || 1;
  // What the axes say, for a reader of the page's text (and its tests).
  canvas.dataset.xLabel = spec.xLabel ?? '';
  canvas.dataset.yLabel = spec.yLabel ?? '';
  const cssW = canvas.clientWidth || 300;
  const cssH = canvas.clientHeight || 150;
  canvas.width = Math.round(cssW * dpr);
  canvas.height = Math.round(cssH * dpr);
  const g = canvas.getContext('2d');
  g.setTransform(dpr, 0, 0, dpr, 0, 0);
  g.clearRect(0, 0, cssW, cssH);
  const font = Math.max(13, parseFloat(getComputedStyle(canvas).fontSize) || 13);
  g.font = `${font}px system-ui, sans-serif`;
  const yTicks = ticks(spec.y[0], spec.y[1], Math.max(4, Math.round(cssH / 35)));
  const digits = yTicks.step < 1 ? Math.min(3, Math.ceil(-Math.log10(yTicks.step))) : 0;
  const yText = yTicks.values.map((v) => formatNumber(v, digits));
  const left = Math.ceil(Math.max(...yText.map((s) => g.measureText(s).width)) + font * 1.6);
  const box = { left, right: cssW - 8, top: font * 0.8, bottom: cssH - font * 2.4 };
  const X = (x) => box.left + ((x - spec.x[0]) / (spec.x[1] - spec.x[0] || 1)) * (box.right - box.left);
  const Y = (y) => box.bottom - ((y - spec.y[0]) / (spec.y[1] - spec.y[0] || 1)) * (box.bottom - box.top);

  // Grid and axes.
  g.lineWidth = 1;
  g.fillStyle = TEXT;
  g.textBaseline = 'middle';
  g.textAlign = 'right';
  yTicks.values.forEach((v, k) => {
    g.strokeStyle = GRID;
    g.beginPath();
    g.moveTo(box.left, Math.round(Y(v)) + 0.5);
    g.lineTo(box.right, Math.round(Y(v)) + 0.5);
    g.stroke();
    g.fillText(yText[k], box.left - 4, Y(v));
  });
  const xTicks = ticks(spec.x[0], spec.x[1], Math.max(2, Math.round(cssW / 70)));
  g.textAlign = 'center';
  g.textBaseline = 'top';
  for (const v of xTicks.values) {
    g.strokeStyle = AXIS;
    g.beginPath();
    g.moveTo(Math.round(X(v)) + 0.5, box.bottom);
    g.lineTo(Math.round(X(v)) + 0.5, box.bottom + 4);
    g.stroke();
    g.fillText(formatNumber(v, xTicks.step < 1 ? 1 : 0), X(v), box.bottom + 5);
  }
  g.strokeStyle = AXIS;
  g.strokeRect(box.left + 0.5, box.top + 0.5, box.right - box.left, box.bottom - box.top);
  if (spec.zeroLine && spec.y[0] < 0 && spec.y[1] > 0) {
    g.beginPath();
    g.moveTo(box.left, Math.round(Y(0)) + 0.5);
    g.lineTo(box.right, Math.round(Y(0)) + 0.5);
    g.stroke();
  }
  if (spec.xLabel) {
    g.textAlign = 'right';
    g.textBaseline = 'bottom';
    g.fillText(spec.xLabel, box.right, cssH - 1);
  }
  if (spec.yLabel) {
    g.save();
    g.translate(font * 0.1, (box.top + box.bottom) / 2);
    g.rotate(-Math.PI / 2);
    g.textAlign = 'center';
    g.textBaseline = 'top';
    g.fillText(spec.yLabel, 0, 0);
    g.restore();
  }

  g.save();
  g.beginPath();
  g.rect(box.left, box.top, box.right - box.left, box.bottom - box.top);
  g.clip();
  for (const v of spec.vlines ?? []) {
    g.strokeStyle = v.color;
    g.lineWidth = v.width ?? 1;
    g.setLineDash(v.dash ?? []);
    g.beginPath();
    g.moveTo(Math.round(X(v.x)) + 0.5, box.top);
    g.lineTo(Math.round(X(v.x)) + 0.5, box.bottom);
    g.stroke();
  }
  for (const s of spec.series) {
    g.strokeStyle = s.color;
    g.lineWidth = (s.width ?? 1.5) * 1.3;
    g.setLineDash(s.dash ?? []);
    g.beginPath();
    let open = false;
    for (const [x, y] of s.points) {
      if (y === null || y === undefined) {
        open = false;
        continue;
      }
      if (open) g.lineTo(X(x), Y(y));
      else g.moveTo(X(x), Y(y));
      open = true;
    }
    g.stroke();
  }
  g.restore();
  return { X, Y, box, toX: (px) => spec.x[0] + ((px - box.left) / (box.right - box.left)) * (spec.x[1] - spec.x[0]) };
}
