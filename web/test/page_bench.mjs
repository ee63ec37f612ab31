// Load and frame times of result pages in headless Chromium (software
// WebGL: SwiftShader, no GPU), for docs/benchmarks.md:
//   node web/test/page_bench.mjs PAGE.html [PAGE.html ...]
// load: from navigation to <body data-cairn-ready> (the data parsed, the
// scene built, the first frame drawn); frame: the mean time to set a tick
// (poses, roles, contacts: simulations) and draw it, over 60 frames.
// Median of three runs, each in a fresh browser.
import { statSync } from 'node:fs';
import { launch, openPage } from './browser.mjs';

const median = (v) => [...v].sort((a, b) => a - b)[Math.floor(v.length / 2)];
for (const file of process.argv.slice(2)) {
  const loads = [], frames = [];
  for (let k = 0; k < 3; ++k) {
    const browser = await launch();
    try {
      const o = await openPage(file, { width: 1280, height: 760 }, browser);
      loads.push(await o.page.evaluate(() => cairn.loadTime()));
      frames.push(await o.page.evaluate(() => cairn.frameTime(60)));
      if (o.errors.length) console.error(o.errors.join('\n'));
    } finally {
      await browser.close();
    }
  }
  const mb = (statSync(file).size / 1e6).toFixed(2);
  console.log(`${file}: ${mb} MB, load ${median(loads).toFixed(0)} ms, frame ${median(frames).toFixed(1)} ms`);
}
