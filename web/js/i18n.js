// String lookup: every visible string comes from a table keyed by name
// (i18n/en.js), so that translations are new tables, not code changes.
import en from '../i18n/en.js';

let table = en;

/** Uses `strings` (same keys as en.js; missing keys fall back to English). */
export function setStrings(strings) {
  table = { ...en, ...strings };
}

/** The string for `key`, with `{name}` replaced by `values.name`. */
export function t(key, values = {}) {
  const text = table[key] ?? en[key];
  if (text === undefined) {
    console.warn(`missing string ${key}`);
    return key;
  }
  return text.replace(/\{(\w+)\}/g, (_, name) => (name in values ? String(values[name]) : `{${name}}`));
}

/** Fills every element with `data-i18n` (text) or `data-i18n-title`/`-aria-label` (attributes). */
export function translateDocument(root = document) {
  for (const el of root.querySelectorAll('[data-i18n]')) el.textContent = t(el.dataset.i18n);
  for (const el of root.querySelectorAll('[data-i18n-title]')) el.title = t(el.dataset.i18nTitle);
  for (const el of root.querySelectorAll('[data-i18n-aria-label]')) el.setAttribute('aria-label', t(el.dataset.i18nAriaLabel));
  document.title = t('app.title');
}

/** Formats an integer with thin grouping, as the page shows counts. */
export function formatCount(n) {
  return Number(n).toLocaleString(t('app.locale'));
}
