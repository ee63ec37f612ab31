// The result pages in a real browser (headless Chromium): ctest's `web.pages`
// (tests/web/CMakeLists.txt). Cairn writes each kind of page from the bundled
// examples, and each is opened from file:// as a user opens it:
//   node web/test/page_test.mjs --cairn build/cairn --root . --out DIR
// Each check below names what it asserts; the first failure ends the run
// with exit 1 and the reason.

import { execFileSync } from 'node:child_process';
import { mkdirSync, writeFileSync, readFileSync, existsSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';
import { kChromium, launch, openPage } from './browser.mjs';

const arg = (name, fallback) => {
  const k = process.argv.indexOf(name);
  return k > 0 ? process.argv[k + 1] : fallback;
};
const cairn = resolve(arg('--cairn', 'build/cairn'));
const root = resolve(arg('--root', '.'));
const out = resolve(arg('--out', '/tmp/cairn-pages'));
mkdirSync(out, { recursive: true });

let failures = 0;
function check(ok, what) {
  console.log((ok ? 'ok   ' : 'FAIL ') + what);
  if (!ok) failures++;
}

// Runs cairn and returns its stdout; its exit code is the verdict (0
// stable, 1 not), both fine here.
function run(args) {
  try {
    return execFileSync(cairn, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'], maxBuffer: 1 << 28 });
  } catch (e) {
    if (e.status !== 1) throw new Error('cairn ' + args.join(' ') + ' exited ' + e.status + ': ' + e.stderr);
    return e.stdout;
  }
}

const ex = (f) => join(root, 'examples', f);
const page = (name) => join(out, name + '.html');

// Pixels of the drawing, read in the page: the share of the canvas that is
// not background, and the colour at a point (CSS pixels).
async function pixels(p, points = []) {
  return p.evaluate((points) => {
    const src = document.querySelector('#view canvas');
    const c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    const img = g.getImageData(0, 0, c.width, c.height).data;
    const bg = [0xf6, 0xf5, 0xf2];
    let drawn = 0;
    for (let k = 0; k < img.length; k += 4)
      if (Math.abs(img[k] - bg[0]) + Math.abs(img[k + 1] - bg[1]) + Math.abs(img[k + 2] - bg[2]) > 30) drawn++;
    const sx = c.width / src.clientWidth, sy = c.height / src.clientHeight;
    const at = points.map(([x, y]) => {
      const k = 4 * (Math.round(y * sy) * c.width + Math.round(x * sx));
      return [img[k], img[k + 1], img[k + 2]];
    });
    return { drawn: drawn / (img.length / 4), at };
  }, points);
}

const near = (rgb, hex, tol = 40) => {
  const want = [1, 3, 5].map((k) => parseInt(hex.slice(k, k + 2), 16));
  return rgb.reduce((s, v, k) => s + Math.abs(v - want[k]), 0) <= tol;
};

async function common(opened, name) {
  check(opened.errors.length === 0, name + ': no console errors or exceptions' + (opened.errors.length ? ' (' + opened.errors.join('; ') + ')' : ''));
  check(opened.requests.length === 0, name + ': no network requests' + (opened.requests.length ? ' (' + opened.requests.join(', ') + ')' : ''));
  const html = readFileSync(page(name), 'utf8');
  check(!/\s(src|href)\s*=\s*["']?(https?:)?\/\//i.test(html), name + ': no src/href to a network address');
  const { drawn } = await pixels(opened.page);
  check(drawn > 0.01, name + ': the drawing is not blank (' + (100 * drawn).toFixed(1) + ' % of the canvas drawn)');
}

// --- the pages ----------------------------------------------------------------
run(['check', ex('paper_fig1.json'), '--without', 'C', '--html', page('fig1_check')]);
run(['check', ex('paper_fig1.json'), '--html', page('fig1_stable')]);
run(['simulate', ex('jenga.json'), join(root, 'examples/plans/jenga_pull_l9.plan.json'), '--html', page('jenga_pull')]);
run(['simulate', ex('paper_fig1.json'), join(root, 'examples/plans/paper_fig1_b_first.plan.json'), '--html', page('fig1_b_first')]);
run(['plan', ex('paper_fig1.json'), '--html', page('fig1_plan')]);
run(['check', ex('jenga.json'), '--html', page('jenga_check')]);
run(['plan', ex('paper_fig9.json'), '--html', page('fig9_plan')]);
run(['margin', ex('jenga.json'), '--tilt', '1,0,0', '--html', page('jenga_tilt')]);
run(['blocking', ex('paper_fig9.json'), '--html', page('fig9_blocking')]);
// Small 3-D pages of each kind, for the screenshots below (the Jenga pull
// stands for the large ones).
run(['check', ex('paper_fig9.json'), '--html', page('fig9_check')]);
run(['sequence', ex('paper_fig9.json'), '--html', page('fig9_sequence')]);
run(['margin', ex('paper_fig9.json'), '--tilt', '1,0,0', '--html', page('fig9_tilt')]);

// A scene whose names would break a naive page: quotes, </script>, <!--, &.
const hostile = {
  cairn: 1, name: 'Evil </script><script>alert(1)</script> "quoted" & <!-- co',
  parts: [
    { name: 'table', fixed: true, polygon: [[-2, -1], [2, -1], [2, 0], [-2, 0]] },
    { name: '</script><img src=x onerror=alert(2)>', polygon: [[-1, 0], [1, 0], [1, 1], [-1, 1]] },
    { name: "it's \"B\" <!-- & \u2028 é", polygon: [[-0.5, 1], [2.5, 1], [2.5, 1.5], [-0.5, 1.5]] },
  ],
};
writeFileSync(join(out, 'hostile.json'), JSON.stringify(hostile));
run(['check', join(out, 'hostile.json'), '--html', page('hostile')]);

// A block jammed between two walls (friction 0.5): an equilibrium squeezes
// it, a rigid motion lets it slide, and loaded from rest it gives way.
const jammed = {
  cairn: 1, name: 'jammed', friction: 0.5,
  parts: [
    { name: 'left', fixed: true, polygon: [[-1, -2], [0, -2], [0, 2], [-1, 2]] },
    { name: 'right', fixed: true, polygon: [[1, -2], [2, -2], [2, 2], [1, 2]] },
    { name: 'block', polygon: [[0, 0], [1, 0], [1, 1], [0, 1]] },
  ],
};
writeFileSync(join(out, 'jammed.json'), JSON.stringify(jammed));
run(['check', join(out, 'jammed.json'), '--html', page('jammed')]);

// Build orders (`cairn sequence --html`): the 3-voussoir arch of the tests
// with props and with holds (2-D), Fig. 17 with a hold, Jenga (3-D).
const arch = { cairn: 1, name: 'arch of 3', friction: 0.6, parts: [
  { name: 'left springer', fixed: true, box: { min: [-1.65, -1], max: [-1, 0] } },
  { name: 'right springer', fixed: true, box: { min: [1, -1], max: [1.65, 0] } }] };
for (let k = 0; k < 3; ++k) {
  const t0 = Math.PI * (1 - k / 3), t1 = Math.PI * (1 - (k + 1) / 3);
  arch.parts.push({ name: 'v' + (k + 1), polygon: [[Math.cos(t0), Math.sin(t0)], [1.15 * Math.cos(t0), 1.15 * Math.sin(t0)],
                                                   [1.15 * Math.cos(t1), 1.15 * Math.sin(t1)], [Math.cos(t1), Math.sin(t1)]] });
}
writeFileSync(join(out, 'arch3.json'), JSON.stringify(arch));
const sequences = {
  arch_props: [join(out, 'arch3.json'), '--temporary', 'prop'],
  arch_holds: [join(out, 'arch3.json'), '--directions', 'axes'],
  fig17_sequence: [ex('paper_fig17.json')],
  jenga_sequence: [ex('jenga.json'), '--beam', '1'],
};
for (const [name, args] of Object.entries(sequences)) run(['sequence', ...args, '--html', page(name)]);

// Real 3-D failures from ../shared (in CI; said plainly when absent): the
// compas_cra shelf at μ 0.84, whose struts 9 and 10 slide out, and the
// 399-block Armadillo vault, which stands.
const shared = join(root, '..', 'shared', 'datasets', 'compas_cra');
const haveShared = existsSync(join(shared, 'shelf.json')) && existsSync(join(shared, 'armadillo_cra.json'));
const shelfArgs = ['check', join(shared, 'shelf.json'), '--format', 'compas', '--friction', '0.84', '--supports', '0'];
if (haveShared) {
  run([...shelfArgs, '--html', page('shelf')]);
  run(['check', join(shared, 'armadillo_cra.json'), '--format', 'compas', '--friction', '0.84', '--interfaces', 'stored',
       '--html', page('armadillo')]);
} else {
  console.log('skip the shelf and the Armadillo: ' + shared + ' is not there (../shared beside the checkout)');
}

const browser = await launch();
const open = (name, viewport) => openPage(page(name), viewport, browser);

// The lines of the text summary that say how a part moves ("  10 slides
// down along (…): centroid …"), up to their colon: the page's story must
// use the same words.
const motionLines = (text) => text.split('\n').filter((l) => /^  \S+ (slides|tips|falls|moves|lifts|rotates)\b/.test(l))
  .map((l) => l.trim().replace(/: centroid .*$/, ''));

// Share of a PNG screenshot's view that is not background, read by the
// browser itself (no image library in the test).
let decoder = null;
async function drawnShare(png) {
  decoder = decoder || (await (await browser.newContext()).newPage());
  return decoder.evaluate(async (b64) => {
    const img = new Image();
    img.src = 'data:image/png;base64,' + b64;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    // The view: left of the side panel (320 px), between header and footer.
    const w = img.width - 330, top = 60, bottom = img.height - 60;
    const d = g.getImageData(0, top, w, bottom - top).data;
    let n = 0;
    for (let k = 0; k < d.length; k += 4) if (Math.abs(d[k] - 0xf6) + Math.abs(d[k + 1] - 0xf5) + Math.abs(d[k + 2] - 0xf2) > 30) n++;
    return n / (d.length / 4);
  }, png.toString('base64'));
}
try {
  // check, 2-D, unstable: Fig. 1 without C. B and D tip: drawn in the
  // failing colour; A stays put: drawn in its own.
  {
    const o = await open('fig1_check');
    await common(o, 'fig1_check');
    const p = o.page;
    check(await p.evaluate(() => document.getElementById('verdict').textContent === 'unstable'), 'fig1_check: the badge says unstable');
    const [b, d, a] = await p.evaluate(() => [cairn.partScreen('B'), cairn.partScreen('D'), cairn.partScreen('A')]);
    // B's centroid is under its motion arrow; a point of B beside it.
    const { at } = await pixels(p, [[b[0] - 30, b[1]], [d[0], d[1] - 8], [a[0] - 20, a[1]]]);
    check(near(at[0], '#e0312b'), 'fig1_check: B is drawn in the failing colour (' + at[0] + ')');
    check(near(at[1], '#e0312b'), 'fig1_check: D is drawn in the failing colour (' + at[1] + ')');
    check(near(at[2], '#d9b26f'), 'fig1_check: A is drawn as a part that stays put (' + at[2] + ')');
    check(await p.evaluate(() => /B tips about \(1, 1\.25\) clockwise/.test(document.getElementById('story').textContent)),
          'fig1_check: the page says B tips about (1, 1.25) clockwise');
    check(await p.evaluate(() => cairn.contactCount()) === 6, 'fig1_check: its 6 contacts are drawn');
    // Hovering B shows its numbers.
    await p.mouse.move(b[0] - 30 + (await p.evaluate(() => document.querySelector('#view canvas').getBoundingClientRect().left)),
                       b[1] + (await p.evaluate(() => document.querySelector('#view canvas').getBoundingClientRect().top)));
    await p.waitForTimeout(100);
    check(await p.evaluate(() => /^B\b[\s\S]*tips about/.test(document.getElementById('tip').textContent)),
          'fig1_check: hovering B shows its name and motion');
    await o.close();
  }
  // Rigid bodies leave it open: the page says what the rigid analysis found
  // and what loading from rest decided, beside each other.
  {
    const o = await open('jammed');
    await common(o, 'jammed');
    const story = await o.page.evaluate(() => document.getElementById('story').textContent);
    check(/Rigid analysis: an equilibrium exists; a rigid motion also exists: block moves/.test(story),
          'jammed: the page gives the rigid analysis (' + story + ')');
    check(/Loaded from rest on compliant contacts: block gives way/.test(story),
          'jammed: the page gives the loaded-from-rest result');
    await o.close();
  }
  {
    const o = await open('fig1_stable');
    await common(o, 'fig1_stable');
    check(await o.page.evaluate(() => document.getElementById('verdict').textContent === 'stable'), 'fig1_stable: the badge says stable');
    await o.close();
  }

  // simulate, 3-D: the Jenga pull. The scrubber moves the pulled block and
  // the chart's marker; the failure is marked.
  {
    const o = await open('jenga_pull');
    await common(o, 'jenga_pull');
    const p = o.page;
    const n = await p.evaluate(() => cairn.frameCount);
    const doc = JSON.parse(run(['simulate', ex('jenga.json'), join(root, 'examples/plans/jenga_pull_l9.plan.json'), '--json']));
    check(n === doc.steps[0].time_steps, 'jenga_pull: one frame per analysed tick (' + n + ')');
    check(await p.evaluate(() => cairn.failureFrame === cairn.frameCount - 1), 'jenga_pull: the failure is the last tick');
    check(await p.evaluate(() => !!document.getElementById('failure-mark')), 'jenga_pull: the failure is marked on the timeline');
    await p.focus('#scrub');
    await p.keyboard.press('Home');
    const first = await p.evaluate(() => [cairn.frame, cairn.partPose('L09_2'), cairn.chartMarkerX(), cairn.partRole('L09_2')]);
    await p.keyboard.press('End');
    const last = await p.evaluate(() => [cairn.frame, cairn.partPose('L09_2'), cairn.chartMarkerX(), cairn.partRole('L09_2')]);
    check(first[0] === 0 && last[0] === n - 1, 'jenga_pull: Home and End on the scrubber go to the first and last tick');
    // The plan pulls L09_2 along +x at 0.04 m/s: at the failure it is
    // 0.04 · t along x (to the page's 7 digits), and has not moved otherwise.
    const dx = last[1][0] - first[1][0], rest = Math.hypot(last[1][1] - first[1][1], last[1][2] - first[1][2]);
    const want = 0.04 * doc.failure.time;
    check(Math.abs(dx - want) < 1e-6 && rest < 1e-6,
          'jenga_pull: the scrubber draws L09_2 pulled ' + dx.toFixed(5) + ' m along x (0.04 m/s × ' + doc.failure.time + ' s)');
    check(last[2] > first[2] + 100, 'jenga_pull: the chart marker follows the scrubber (' + first[2].toFixed(0) + ' → ' + last[2].toFixed(0) + ' px)');
    check(first[3] === 'gripped' && last[3] === 'failed', 'jenga_pull: L09_2 gripped, then failed at the failure (' + first[3] + ', ' + last[3] + ')');
    await o.close();
  }
  // Clicking a pair's resultant shows its numbers and plots the pair; with
  // every contact point drawn, clicking a point does the same for its pair.
  {
    const o = await open('fig1_b_first');
    await common(o, 'fig1_b_first');
    const p = o.page;
    const box = await p.evaluate(() => document.querySelector('#view canvas').getBoundingClientRect().toJSON());
    // Clicks the first of `count` marks whose parts include D; its parts.
    const clickOnD = async (count, partsOf, screenOf) => {
      for (let k = 0; k < count; ++k) {
        const parts = await p.evaluate(partsOf, k);
        if (!parts.includes('D')) continue;
        const [x, y] = await p.evaluate(screenOf, k);
        await p.mouse.click(box.x + x, box.y + y);
        return parts;
      }
      return null;
    };
    const pairClicked = await clickOnD(await p.evaluate(() => cairn.pairCount()), (j) => cairn.pairParts(j), (j) => cairn.pairScreen(j));
    const pairInfo = await p.evaluate(() => document.getElementById('info').textContent);
    check(pairClicked !== null && /pushes/.test(pairInfo) && /resultant on /.test(pairInfo),
          'fig1_b_first: clicking a pair\'s resultant shows it (' + pairInfo.split('\n')[0] + ')');
    check(pairClicked && (await p.evaluate(() => cairn.chartPair())).sort().join() === [...pairClicked].sort().join(),
          'fig1_b_first: and plots its pair');
    await p.evaluate(() => cairn.setForceMode('points'));
    const clicked = await clickOnD(await p.evaluate(() => cairn.contactCount()), (k) => cairn.contactParts(k), (k) => cairn.contactScreen(k));
    check(clicked !== null, 'fig1_b_first: a contact of D is drawn');
    const info = await p.evaluate(() => document.getElementById('info').textContent);
    check(/^contact /.test(info) && /normal force: /.test(info), 'fig1_b_first: clicking it shows its numbers (' + info.split('\n')[0] + ')');
    const pair = await p.evaluate(() => cairn.chartPair());
    check(clicked && pair.join() === clicked.join(), 'fig1_b_first: and plots its pair (' + pair.join('–') + ')');
    // The pair list: choosing A – E plots it.
    const options = await p.evaluate(() => [...document.querySelectorAll('#pair option')].map((o) => o.textContent));
    check(options.includes('A – E'), 'fig1_b_first: the pair list has A – E (' + options.join(', ') + ')');
    await p.selectOption('#pair', { label: 'A – E' });
    check((await p.evaluate(() => cairn.chartPair())).sort().join() === 'A,E', 'fig1_b_first: choosing A – E plots it');
    await o.close();
  }

  // plan: the sequences are listed and play step by step.
  {
    const o = await open('fig1_plan');
    await common(o, 'fig1_plan');
    const p = o.page;
    const n = await p.evaluate(() => document.querySelectorAll('#seqs li').length);
    check(n === 7, 'fig1_plan: its 7 stable sequences are listed (' + n + ')');
    await p.click('#seqs li:nth-child(2)');
    const steps = await p.evaluate(() => [...document.querySelectorAll('#steps li')].map((li) => li.textContent));
    check(steps.length === 3 && /^A\+B/.test(steps[2]), 'fig1_plan: clicking sequence 2 shows its 3 steps (' + steps.join(' | ') + ')');
    const d0 = await p.evaluate(() => { cairn.setPlanTime(0); return cairn.partPose('D'); });
    const d1 = await p.evaluate(() => { cairn.setPlanTime(0.5); return cairn.partPose('D'); });
    check(Math.abs(d1[1] - d0[1] - 1.0) < 1e-9, 'fig1_plan: half way through step 1, D is 1 up (half of its 2)');
    const gone = await p.evaluate(() => { cairn.setPlanTime(1.2); return cairn.partVisible('D'); });
    check(!gone, 'fig1_plan: in step 2, D (removed in step 1) is gone');
    const contacts = await p.evaluate(() => { cairn.setPlanTime(1); return cairn.contactCount(); });
    check(contacts > 0, 'fig1_plan: at the start of a step the rest forces are drawn (' + contacts + ' contacts)');
    await o.close();
  }

  // 3-D check.
  {
    const o = await open('jenga_check');
    await common(o, 'jenga_check');
    await o.close();
  }

  // The hostile names: the page still loads and shows them as text.
  {
    const o = await open('hostile');
    await common(o, 'hostile');
    const p = o.page;
    check(await p.evaluate(() => document.title.startsWith('Evil </script><script>alert(1)</script> "quoted" & <!-- co')),
          'hostile: the title is the scene name, as text');
    check(await p.evaluate(() => cairn.partRole('</script><img src=x onerror=alert(2)>') !== undefined &&
                                 cairn.partRole("it's \"B\" <!-- & \u2028 é") !== undefined),
          'hostile: the parts keep their names');
    check(await p.evaluate(() => document.querySelectorAll('img, script[src]').length === 0), 'hostile: no element was injected');
    await o.close();
  }

  // Build orders: every state steps through, and at each the supports drawn
  // are the document's (held parts in their colour, one arrow per prop);
  // while a part comes in it is drawn gripped, away from its place.
  for (const [name, args] of Object.entries(sequences)) {
    const o = await open(name);
    await common(o, name);
    const p = o.page;
    const doc = JSON.parse(run(['sequence', ...args, '--json']));
    check(await p.evaluate(() => document.querySelectorAll('#steps li').length) === doc.steps.length,
          name + ': its ' + doc.steps.length + ' steps are listed');
    let same = true, gripped = true, forces = true;
    const diffs = [];
    for (let k = 1; k <= doc.steps.length; ++k) {
      const st = doc.steps[k - 1];
      const drawn = await p.evaluate((k) => { cairn.setBuildTime(k); return { ...cairn.supportsDrawn(), contacts: cairn.contactCount() }; }, k);
      const held = st.temporary_in_place.filter((t) => t.kind === 'hold').map((t) => t.part).sort();
      const props = st.temporary_in_place.filter((t) => t.kind === 'prop').length;
      if (drawn.held.join() !== held.join() || drawn.props !== props) {
        same = false;
        diffs.push('step ' + k + ': drawn ' + JSON.stringify(drawn) + ', document ' + held.join() + ' + ' + props + ' props');
      }
      forces = forces && drawn.contacts > 0;
      const arriving = await p.evaluate(([k, part]) => { cairn.setBuildTime(k - 0.5); return [cairn.partRole(part), cairn.partVisible(part)]; }, [k, st.place]);
      gripped = gripped && arriving[0] === 'gripped' && arriving[1];
    }
    check(same, name + ': at every state the supports drawn are the document\'s' + (diffs.length ? ' (' + diffs.join('; ') + ')' : ''));
    check(forces, name + ': every state is drawn with its contact forces');
    check(gripped, name + ': each part is drawn gripped while it comes in');
    const peak = doc.temporary.max_in_place;
    const marked = await p.evaluate(() => document.querySelectorAll('#steps li.peak').length);
    check(peak === 0 ? marked === 0 : marked === doc.steps.filter((s) => s.temporary_in_place.length === peak).length,
          name + ': the steps with the most supports (' + peak + ') are marked (' + marked + ')');
    await o.close();
  }

  // The failing parts always in view and named. On the shelf at μ 0.84
  // struts 9 and 10 slide out; strut 10 stands behind the frame's top beam.
  // From the opening camera, each shows at least 90 % of the pixels it
  // covers when drawn alone, mostly in the failing colour (the frame and
  // strut 8 in front of it drawn see-through: opaque, strut 10 showed 64 %),
  // and carries its name.
  if (haveShared) {
    const o = await open('shelf');
    await common(o, 'shelf');
    const p = o.page;
    for (const part of ['9', '10']) {
      const px = await p.evaluate((part) => cairn.visiblePixels(part), part);
      check(px.alone > 200 && px.pixels >= 0.9 * px.alone && px.red >= 0.5 * px.pixels,
            'shelf: strut ' + part + ' shows from the opening camera (' + px.pixels + ' of its ' + px.alone + ' pixels, ' + px.red + ' red)');
    }
    const labels = await p.evaluate(() => cairn.labels());
    check(labels.includes('9') && labels.includes('10'), 'shelf: the struts that slide are named on the drawing (' + labels.join(', ') + ')');
    check((await p.evaluate(() => cairn.xrayParts())).includes('0'), 'shelf: the frame in front of strut 10 is drawn see-through');
    // The story in the words of the text summary, with why.
    const story = await p.evaluate(() => document.getElementById('story').textContent);
    const lines = motionLines(run(shelfArgs));
    check(lines.length === 2 && lines.every((l) => story.includes(l + ', because no equilibrium exists')),
          'shelf: the story says what the CLI says, and why (' + lines.join(' | ') + ')');
    check(/10 slides down along/.test(story), 'shelf: strut 10 slides down');
    // The legend lists only the roles drawn.
    const legend = await p.evaluate(() => document.getElementById('legend').textContent);
    check(!/gripped|tool|held|fixel/.test(legend) && /moves: fails/.test(legend), 'shelf: the legend shows only the roles present');
    await o.close();
  }
  // The Jenga pull opens on its failure, with L09_2 in view and named.
  {
    const o = await open('jenga_pull');
    const p = o.page;
    const px = await p.evaluate(() => cairn.visiblePixels('L09_2'));
    check(px.alone > 200 && px.pixels >= 0.9 * px.alone && px.red >= 0.5 * px.pixels,
          'jenga_pull: L09_2 shows from the opening camera, in the failing colour (' + px.pixels + ' of ' + px.alone + ' pixels, ' + px.red + ' red)');
    check((await p.evaluate(() => cairn.labels())).includes('L09_2'), 'jenga_pull: L09_2 is named on the drawing');
    await o.close();
  }
  // Fig. 1 without C: the story's motions are the text summary's.
  {
    const o = await open('fig1_check');
    const story = await o.page.evaluate(() => document.getElementById('story').textContent);
    const lines = motionLines(run(['check', ex('paper_fig1.json'), '--without', 'C']));
    check(lines.length === 2 && lines.every((l) => story.includes(l)), 'fig1_check: the story says what the CLI says (' + lines.join(' | ') + ')');
    await o.close();
  }
  // Forces a reader can take in: the Armadillo draws one arrow per pair of
  // parts with a force (its 5 031 contact points on demand), and names its
  // most loaded joints.
  if (haveShared) {
    const o = await open('armadillo');
    await common(o, 'armadillo');
    const p = o.page;
    const [arrows, pairs] = await p.evaluate(() => [cairn.arrowCount(), cairn.pairCount()]);
    check(pairs > 300 && arrows <= pairs, 'armadillo: at most one arrow per pair by default (' + arrows + ' arrows, ' + pairs + ' pairs)');
    const every = await p.evaluate(() => { cairn.setForceMode('points'); const n = cairn.arrowCount(); cairn.setForceMode('pairs'); return n; });
    check(every > 2 * pairs, 'armadillo: every contact point\'s arrows on demand (' + every + ')');
    const joints = await p.evaluate(() => cairn.labels());
    check(joints.length === 3 && joints.every((l) => / pushes .*: [0-9.]+ /.test(l)), 'armadillo: its 3 most loaded joints are named (' + joints.join(' | ') + ')');
    await o.close();
  }

  // A margin: the critical tilt of the Jenga tower, one sense at a time;
  // the story is the text summary; the mechanism's parts are drawn failing
  // and its playback moves each along its own motion.
  {
    const o = await open('jenga_tilt');
    await common(o, 'jenga_tilt');
    const p = o.page;
    const doc = JSON.parse(run(['margin', ex('jenga.json'), '--tilt', '1,0,0', '--json'])).margin;
    const text = run(['margin', ex('jenga.json'), '--tilt', '1,0,0']).split('\n').map((l) => l.trim()).filter((l) => l);
    const story = await p.evaluate(() => [...document.querySelectorAll('#story li')].map((li) => li.textContent));
    check(JSON.stringify(story) === JSON.stringify(text), 'jenga_tilt: the story is the text summary, line by line');
    check(await p.evaluate(() => document.getElementById('verdict').textContent) === 'stands · tilt -15.01° / 15.01°',
          'jenga_tilt: the badge gives both critical tilts');
    for (const sense of ['negative', 'positive']) {
      await p.selectOption('#sense', sense);
      const cert = doc.certificates.find((c) => c.sense === sense);
      const moved = cert.mechanism.parts.map((x) => x.part).sort();
      const failing = await p.evaluate((names) => names.filter((n) => cairn.partRole(n) === 'failed'), moved);
      const others = await p.evaluate(() => ['L01_1', 'L01_3'].map((n) => cairn.partRole(n)));
      check(failing.length === moved.length && others.filter((r) => r === 'failed').length === 1,
            'jenga_tilt: the ' + sense + ' sense draws its mechanism\'s ' + moved.length + ' parts failing, and only those');
      // Played to its end, a part of the mechanism is moved by its unit
      // twist times 5 % of the scene (a point at the centroid: its linear part).
      const x = cert.mechanism.parts[0];
      const [size, at0, at1] = await p.evaluate((name) => {
        cairn.setMechanismPhase(0);
        const a = cairn.partPose(name);
        cairn.setMechanismPhase(1);
        const b = cairn.partPose(name);
        return [JSON.parse(document.getElementById('cairn-data').textContent).scene.size, a, b];
      }, x.part);
      const want = x.linear.map((v) => v * 0.05 * size);
      check([0, 1, 2].every((k) => Math.abs(at1[k] - at0[k] - want[k]) < 1e-6 * size),
            'jenga_tilt: ' + x.part + ' moves along its mechanism motion (' + want.map((v) => v.toFixed(4)).join(', ') + ')');
    }
    await o.close();
  }
  // A blocking graph: every cell listed; a cell chosen draws the parts that
  // can leave along it as free, each with an arrow, and names them.
  {
    const o = await open('fig9_blocking');
    await common(o, 'fig9_blocking');
    const p = o.page;
    const doc = JSON.parse(run(['blocking', ex('paper_fig9.json'), '--json']));
    check(await p.evaluate(() => document.querySelectorAll('#cells li').length) === doc.cells.length,
          'fig9_blocking: its ' + doc.cells.length + ' cells are listed');
    let same = true;
    for (let k = 0; k < doc.cells.length; ++k) {
      const drawn = await p.evaluate((k) => { cairn.selectCell(k); return [cairn.supportsDrawn(), cairn.labels()]; }, k);
      const free = await p.evaluate((names) => names.filter((n) => cairn.partRole(n) === 'free'), doc.cells[k].removable);
      const labels = drawn[1];
      same = same && free.length === doc.cells[k].removable.length && doc.cells[k].removable.every((n) => labels.includes(n));
    }
    check(same, 'fig9_blocking: each cell draws and names the parts that can leave along it');
    // The story is the text summary's headline, whole (its explanation of
    // the text's columns is not the page's).
    const headline = run(['blocking', ex('paper_fig9.json')]).split('\n')[0];
    const story = await p.evaluate(() => [...document.querySelectorAll('#story li')].map((li) => li.textContent));
    check(story.length === 1 && story[0] === headline, 'fig9_blocking: the story is the summary\'s headline (' + story.join(' | ') + ')');
    await o.close();
  }

  // Drawn on every load: 10 screenshots of each kind of 3-D page, each
  // taken as soon as the page's load event has fired (not waiting for
  // data-cairn-ready), and for a check and a simulation one by Chromium's
  // own --screenshot (2–3 s each under the sanitizers' load); none blank.
  {
    const kinds = { fig9_check: 'check', jenga_pull: 'simulate', fig9_plan: 'plan', fig9_sequence: 'sequence',
                    fig9_tilt: 'margin', fig9_blocking: 'blocking' };
    const byChromium = new Set(['fig9_check', 'jenga_pull']);
    // A smaller window than the other checks': a try costs its load (the
    // script's compile, the scene) more than its pixels.
    const ctx = await browser.newContext({ viewport: { width: 800, height: 500 } });
    for (const [name, kind] of Object.entries(kinds)) {
      const shares = [];
      for (let k = 0; k < 10; ++k) {
        const p = await ctx.newPage();
        await p.goto(pathToFileURL(page(name)).href, { waitUntil: 'load' });
        shares.push(await drawnShare(await p.screenshot()));
        await p.close();
      }
      if (byChromium.has(name)) {
        const shot = join(out, name + '.cli.png');
        execFileSync(kChromium, ['--headless', '--no-sandbox', '--screenshot=' + shot, '--window-size=1280,760',
                                 pathToFileURL(page(name)).href], { stdio: 'ignore', timeout: 60000 });
        shares.push(await drawnShare(readFileSync(shot)));
      }
      check(shares.every((x) => x > 0.02), 'a ' + kind + ' page (' + name + '): none of ' + shares.length + ' screenshots is blank (drawn: ' +
            shares.map((x) => (100 * x).toFixed(0) + '%').join(' ') + ')');
    }
    await ctx.close();
  }

  // Determinism: the same command writes the same page.
  run(['check', ex('paper_fig1.json'), '--without', 'C', '--html', join(out, 'again.html')]);
  check(readFileSync(join(out, 'again.html'), 'utf8') === readFileSync(page('fig1_check'), 'utf8'), 'the same command writes the same page byte for byte');
} finally {
  await browser.close();
}
if (!existsSync(cairn)) failures++;
console.log(failures ? failures + ' check(s) failed' : 'all checks passed');
process.exit(failures ? 1 : 0);
