// Opens a page in headless Chromium and writes a screenshot (for docs and
// debugging):  node test/shot.mjs PAGE.html OUT.png [WIDTH HEIGHT] [SCRIPT]
// SCRIPT is run in the page (e.g. "cairn.setFrame(46)") before the shot.
import { openPage } from './browser.mjs';

const [page_file, out, w = '1280', h = '760', script = ''] = process.argv.slice(2);
const { close, page, errors } = await openPage(page_file, { width: Number(w), height: Number(h) });
try {
  if (script) {
    await page.evaluate(script);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  }
  await page.screenshot({ path: out });
  if (errors.length) console.error('page errors:\n' + errors.join('\n'));
} finally {
  await close();
}
