// Headless Chromium (Debian's /usr/bin/chromium) driven by playwright-core:
// the flags that let it run as root, without a GPU and on a closed network.
import { chromium } from 'playwright-core';
import { pathToFileURL } from 'node:url';
import { resolve } from 'node:path';

export const kChromium = process.env.CAIRN_CHROMIUM || '/usr/bin/chromium';

export async function launch() {
  return chromium.launch({
    executablePath: kChromium,
    args: ['--no-sandbox', '--headless=new', '--enable-unsafe-swiftshader', '--use-angle=swiftshader',
           '--disable-background-networking', '--disable-component-update', '--no-first-run',
           '--disable-sync', '--disable-quic', '--disable-dev-shm-usage'],
  });
}

// Opens `file` (a page Cairn wrote) from file:// and waits for
// <body data-cairn-ready="true">. Returns the page and every console error
// and uncaught exception seen.
export async function openPage(file, viewport = { width: 1280, height: 760 }, browser = null) {
  const own = !browser;
  browser = browser || (await launch());
  const context = await browser.newContext({ viewport });
  const page = await context.newPage();
  const errors = [];
  const requests = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push('console: ' + m.text()); });
  page.on('pageerror', (e) => errors.push('exception: ' + e.message));
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) requests.push(r.url()); });
  const t0 = Date.now();
  await page.goto(pathToFileURL(resolve(file)).href);
  await page.waitForSelector('body[data-cairn-ready="true"]', { timeout: 60000 });
  const loadMs = Date.now() - t0;
  return { browser: own ? browser : null, owner: browser, context, page, errors, requests, loadMs,
           close: async () => { await context.close(); if (own) await browser.close(); } };
}
