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
