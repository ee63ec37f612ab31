// Bundles the page's script (src/main.js with three.js) into one minified
// IIFE, dist/viewer.js, which the C++ build embeds in every --html page
// (cmake/embed_viewer.cmake). The bundle is committed, so building Cairn
// needs no Node.js; run `npm run build` (after `npm ci`) when src/ changes.
import { build } from 'esbuild';
import { readFileSync, writeFileSync } from 'node:fs';

await build({
  entryPoints: ['src/main.js'],
  bundle: true,
  format: 'iife',
  minify: true,
  target: ['es2020'],
  legalComments: 'none',
  outfile: 'dist/viewer.js',
});
// The script is inlined in <script>: it must not contain "</script".
const js = readFileSync('dist/viewer.js', 'utf8');
if (/<\/script/i.test(js)) throw new Error('dist/viewer.js contains </script');
const three = JSON.parse(readFileSync('node_modules/three/package.json', 'utf8'));
writeFileSync('dist/viewer.js', `/* Cairn viewer; three.js ${three.version} (MIT, (c) 2010-2025 three.js authors) */\n` + js);
console.log(`dist/viewer.js: ${(js.length / 1024).toFixed(0)} kB`);
