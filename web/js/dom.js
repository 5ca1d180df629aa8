// Building the page's elements: one small helper.

/**
 * A new element: `attrs` are attributes, but `text` sets its text, `style`
 * (an object of CSS properties) its style through the CSSOM, which the
 * server's Content-Security-Policy allows where a style attribute is not,
 * and non-string values set properties (`disabled: true`, `onclick: f`).
 */
export function el(tag, attrs = {}, children = []) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null) continue;
    if (k === 'text') e.textContent = v;
    else if (k === 'style') for (const [p, x] of Object.entries(v)) e.style.setProperty(p, x);
    else if (k in e && typeof v !== 'string') e[k] = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) if (c !== null && c !== undefined && c !== false) e.append(c);
  return e;
}

/**
 * Sets `target[prop]` only when it differs: what runs after every frame or
 * change (each orbit step) would otherwise make the browser lay the page
 * out again for a value, bound or text it already has.
 */
export function put(target, prop, value) {
  if (target[prop] !== value) target[prop] = value;
}

const beforePaint = new Set();
/** When the work waiting for the next animation frame was first asked for. */
let waitingSince = 0;
let holding = () => false;
/** The longest the work of `beforeNextPaint` waits for `holding` to end, ms. */
const HOLD_MS = 50;

/**
 * Runs `fn` at an animation frame, once however often it is asked for
 * before then: what only the eye needs when the state changes or a frame
 * arrives (captions, marks, the controls' values) waits for the paint that
 * shows it. While `holding()` is true (a panel is still drawing), it waits
 * further, up to HOLD_MS, so that the page lays itself out once the frames
 * are in rather than while they arrive: a frame that arrives while the page
 * is being laid out waits for it before it can be put on its canvas.
 */
export function beforeNextPaint(fn) {
  if (beforePaint.size === 0) {
    waitingSince = performance.now();
    requestAnimationFrame(runBeforePaint);
  }
  beforePaint.add(fn);
}

function runBeforePaint() {
  if (holding() && performance.now() - waitingSince < HOLD_MS) {
    requestAnimationFrame(runBeforePaint);
    return;
  }
  const due = [...beforePaint];
  beforePaint.clear();
  for (const f of due) f();
}

/** Makes `beforeNextPaint`'s work wait while `predicate()` is true (see there). */
export function holdPaintWorkWhile(predicate) {
  holding = predicate;
}

/** Whether something waits for an animation frame (`beforeNextPaint`). */
export const paintPending = () => beforePaint.size > 0;
