// String lookup: every visible string comes from a table keyed by name
// (i18n/en.js and its translations ru.js, sk.js, cs.js), so that a language
// is a new table, not a code change. The instruments' own texts (the
// explanations of each method, the inspector's sentences) come from the
// shadelab-lab crate through the WebAssembly, in the same language: `lab(id)`.
import en from '../i18n/en.js';
import { LANGUAGES } from './state.js';

let table = en;
let labTexts = {};
let current = 'en';

/** The names of the languages, each in itself (for the switch). */
export const LANGUAGE_NAMES = { en: 'English', ru: 'Русский', sk: 'Slovenčina', cs: 'Čeština' };

/** The first of the browser's preferred languages (BCP 47 tags) that the page speaks, else English. */
export function negotiate(preferred) {
  for (const tag of preferred ?? []) {
    const primary = String(tag).split(/[-_]/)[0].toLowerCase();
    if (LANGUAGES.includes(primary)) return primary;
  }
  return 'en';
}

/**
 * Switches to language `lang`: loads its table and, through `loadLabTexts(lang)`,
 * the instruments' texts. Missing keys fall back to English (a test keeps the
 * tables complete).
 */
export async function setLanguage(lang, loadLabTexts) {
  const strings = lang === 'en' ? en : (await import(`../i18n/${lang}.js`)).default;
  const lab = await loadLabTexts(lang);
  table = { ...en, ...strings };
  labTexts = lab;
  current = lang;
  document.documentElement.lang = lang;
}

/** The language in use. */
export function language() {
  return current;
}

/** The string for `key`, with `{name}` replaced by `values.name`. */
export function t(key, values = {}) {
  const text = table[key] ?? en[key];
  if (text === undefined) {
    console.warn(`missing string ${key}`);
    return key;
  }
  return fill(text, values);
}

/**
 * The string for `key`, or undefined when no table has it: a parameter's
 * label then comes from the core's table (form.js: labelOf).
 */
export function translation(key, values = {}) {
  const text = table[key] ?? en[key];
  return text === undefined ? undefined : fill(text, values);
}

/** The instruments' text `id` (shadelab-lab's texts/*.toml), filled like `t`. */
export function lab(id, values = {}) {
  const text = labTexts[id];
  if (text === undefined) {
    console.warn(`missing text ${id}`);
    return id;
  }
  return fill(text, values);
}

function fill(text, values) {
  return text.replace(/\{(\w+)\}/g, (_, name) => (name in values ? String(values[name]) : `{${name}}`));
}

/** Fills every element with `data-i18n` (text) or `data-i18n-title`/`-aria-label` (attributes). */
export function translateDocument(root = document) {
  for (const el of root.querySelectorAll('[data-i18n]')) el.textContent = t(el.dataset.i18n);
  for (const el of root.querySelectorAll('[data-i18n-title]')) el.title = t(el.dataset.i18nTitle);
  for (const el of root.querySelectorAll('[data-i18n-aria-label]')) el.setAttribute('aria-label', t(el.dataset.i18nAriaLabel));
  document.title = t('app.title');
}

/**
 * A count in words: `key`'s form for `n` in the language (`key.one`,
 * `key.few`, `key.many` or `key.other`, as Intl.PluralRules chooses), with
 * `{n}` the count formatted as the page shows counts.
 */
export function plural(key, n, values = {}) {
  const locale = t('app.locale');
  const category = made(`plural ${locale}`, () => new Intl.PluralRules(locale)).select(n);
  const form = `${key}.${category}` in table ? `${key}.${category}` : `${key}.other`;
  return t(form, { n: formatCount(n), ...values });
}

/** Formats an integer with the language's grouping, as the page shows counts. */
export function formatCount(n) {
  const locale = t('app.locale');
  return made(`count ${locale}`, () => new Intl.NumberFormat(locale)).format(Number(n));
}

/** Formats a number with `digits` decimals in the language's style (decimal comma in ru, sk, cs). */
export function formatNumber(x, digits) {
  const locale = t('app.locale');
  const options = { minimumFractionDigits: digits, maximumFractionDigits: digits, useGrouping: false };
  return made(`number ${locale} ${digits}`, () => new Intl.NumberFormat(locale, options)).format(Number(x));
}

const intl = new Map();
/**
 * The `Intl` object named `key`, made by `make` the first time: making one
 * costs far more than using it, and the captions use them for every frame
 * (`toLocaleString` makes a new one on each call).
 */
function made(key, make) {
  let object = intl.get(key);
  if (object === undefined) {
    object = make();
    intl.set(key, object);
  }
  return object;
}
