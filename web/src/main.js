// Cairn's result page (`--html`): reads the data the command embedded
// (<script id="cairn-data" type="application/json">) and draws it: the
// scene, the verdict and its evidence (forces, the parts that move and how),
// a time scrubber over a simulation's ticks with a force-versus-time chart,
// a plan's sequences step by step. docs/html.md describes the page and the
// data; `window.cairn` is the page's small API for scripts and tests.

import * as THREE from 'three';
import { kColors, kCss } from './style.js';
import { SceneView, contactsFromReport, emptyContacts, pad3 } from './scene_view.js';
import { ForceChart } from './chart.js';

const $ = (tag, attrs = {}, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
};
// On a stable check, this many of the largest resultants per pair of parts
// are named on the drawing.
const kMostLoadedJoints = 3;
// A margin's mechanism is played out to this share of the scene's size.
const kMechanismReach = 0.05;
const fmt = (x, digits = 4) => (typeof x === 'number' ? Number(x.toPrecision(digits)).toString() : String(x));
const vec = (v) => '(' + pad3(v).slice(0, v && v.length === 2 ? 2 : 3).map((x) => fmt(x)).join(', ') + ')';

function main() {
  const style = document.createElement('style');
  style.textContent = kCss;
  document.head.appendChild(style);
  const data = JSON.parse(document.getElementById('cairn-data').textContent);
  const page = new Page(data);
  window.cairn = page.api();
  page.start();
}

// The rigid analysis and the loaded-from-rest result beside it
// (docs/loaded-from-rest.md), as the check's JSON has them: what is proved
// about rest, the rigid motion found, and what loading from rest decided.
function analysisWords(r) {
  const lines = [];
  const comps = r.components || [];
  const rigid = [...new Set(comps.flatMap((c) => c.rigid_motion || []))];
  const search = comps.map((c) => c.search).filter((s) => s);
  if (r.static_equilibrium === true) {
    let rigidLine = 'Rigid analysis: an equilibrium exists';
    if (r.stability === 'strong') rigidLine += '; every solution of the contact problem is at rest (strongly stable)';
    else if (rigid.length) rigidLine += '; a rigid motion also exists: ' + rigid.join(', ') + (rigid.length === 1 ? ' moves' : ' move') + ' (weakly stable)';
    else if (r.stability === 'not certified')
      rigidLine += '; no rigid motion found' + (search.some((s) => s.outcome === 'budget')
        ? ' (the search stopped at its budget after ' + search.reduce((n, s) => n + s.nodes, 0) + ' branches)' : '');
    lines.push(rigidLine + '.');
  } else if (r.static_equilibrium === false) {
    lines.push('Rigid analysis: no equilibrium exists.');
  }
  if (r.loaded_from_rest === 'stands') lines.push('Loaded from rest on compliant contacts: it stands.');
  else if (r.loaded_from_rest === 'gives way') {
    const parts = [...new Set(comps.flatMap((c) => (c.loaded_from_rest && c.loaded_from_rest.gives_way) || []))];
    lines.push('Loaded from rest on compliant contacts: ' + (parts.length ? parts.join(', ') : 'it') +
               ' gives way: nothing produces the forces the equilibrium needs.');
  } else if (r.loaded_from_rest) {
    lines.push('Loaded from rest: ' + r.loaded_from_rest + '; the equilibrium decides.');
  }
  return lines;
}

class Page {
  constructor(data) {
    this.data = data;
    this.scene = data.scene;
    this.result = data.result || {};
    this.names = this.scene.parts.map((p) => p.name);
    this.index = new Map(this.names.map((n, i) => [n, i]));
    this.unit = this.result.force_unit || this.scene.force_unit || 'force units';
    this.indexOf = (name) => (this.index.has(name) ? this.index.get(name) : -1);
    // The frames' and plan nodes' contacts are the records --json writes;
    // the drawing takes them in compact form.
    for (const f of data.frames || []) f.contacts = contactsFromReport(f.contacts, this.indexOf);
    const nodes = (data.plan && data.plan.nodes) || {};
    for (const key of Object.keys(nodes)) nodes[key] = contactsFromReport(nodes[key], this.indexOf);
    this.buildLayout();
    this.view = new SceneView(this.viewEl, this.scene);
    this.view.setForceReference(this.forceReference());
    this.view.setFixels(this.scene.fixtures || []);
    this.bindPicking();
  }

  // The force an arrow of 12 % of the scene stands for (stated in the
  // legend): the largest normal force the page shows, at any tick or node;
  // without contacts, the heaviest movable part's weight.
  forceReference() {
    let m = 0;
    const scan = (fn) => { for (const x of fn) m = Math.max(m, x); };
    for (const c of this.result.contacts || []) m = Math.max(m, c.normal_force || 0);
    for (const f of this.data.frames || []) scan(f.contacts.fn);
    for (const c of Object.values((this.data.plan && this.data.plan.nodes) || {})) scan(c.fn);
    for (const c of (this.data.sequence && this.data.sequence.states) || []) for (const k of c || []) m = Math.max(m, k.normal_force || 0);
    for (const c of (this.result.margin && this.result.margin.certificates) || [])
      for (const k of (c.equilibrium && c.equilibrium.contacts) || []) m = Math.max(m, k.normal_force || 0);
    return m > 0 ? m : this.scene.force_reference > 0 ? this.scene.force_reference : 1;
  }

  // --- layout --------------------------------------------------------------
  buildLayout() {
    const d = this.data, r = this.result;
    const verdict = d.kind === 'plan' ? planVerdict(r) : d.kind === 'sequence' ? (r.complete ? 'built' : 'incomplete')
      : d.kind === 'margin' ? marginVerdict(r.margin || {})
      : d.kind === 'blocking' ? (r.cells || []).length + ' cell' + ((r.cells || []).length === 1 ? '' : 's')
      : r.verdict || (r.stable ? 'stable' : 'unstable');
    const good = verdict === 'stable' || verdict === 'planned' || verdict === 'built' || /^stands|cell/.test(verdict);
    this.app = document.getElementById('cairn-app') || document.body.appendChild($('div', { id: 'cairn-app' }));
    const head = $('header', {},
      $('h1', {}, d.title || this.scene.name || 'Cairn'),
      $('span', { class: 'kind' }, 'cairn ' + d.kind + (this.scene.file ? ' · ' + this.scene.file : '')),
      $('span', { class: 'badge ' + (good ? 'good' : verdict === 'infeasible' ? 'warn' : 'bad'), id: 'verdict' }, verdict));
    this.viewEl = $('div', { id: 'view' });
    this.tip = $('div', { id: 'tip' });
    this.overlayEl = $('div', { id: 'overlay' }, this.scene.dimension === 2 ? 'drag: pan · wheel: zoom' : 'drag: orbit · right-drag: pan · wheel: zoom');
    this.viewEl.append(this.tip, this.overlayEl);
    this.side = $('aside', {});
    this.foot = $('footer', {});
    this.app.append(head, this.viewEl, this.side, this.foot);
    this.storyEl = $('ol', { id: 'story' });
    this.infoEl = $('div', { id: 'info' }, 'Hover or click a part or a contact point.');
    this.side.append($('h2', {}, 'What happens'), this.storyEl);
    this.extraSide = $('div', {});
    this.legendEl = $('div', { class: 'legend', id: 'legend' });
    this.side.append(this.extraSide, $('h2', {}, 'Selected'), this.infoEl, $('h2', {}, 'Legend'), this.legendEl);
  }

  // The roles the page draws at some point (for the legend): the scene's
  // own, and those of the result's frames, steps and supports.
  rolesPresent() {
    const roles = new Set(this.scene.parts.map((p) => (p.fixed ? 'fixed' : p.tool ? 'tool' : 'judged')));
    const d = this.data, r = this.result;
    if (d.kind === 'check' && (r.moving || []).length) roles.add('failed');
    if (d.kind === 'margin' && ((r.margin || {}).certificates || []).some((c) => c.mechanism && c.mechanism.found)) roles.add('failed');
    for (const f of d.frames || []) for (const [, role] of f.roles || []) roles.add(role);
    if (d.kind === 'simulate' && r.failure) roles.add('failed');
    if (d.kind === 'plan' && (r.sequences || []).length) roles.add('gripped');
    if (d.kind === 'sequence' && (r.steps || []).length) roles.add('gripped');
    if (d.kind === 'blocking' && (r.cells || []).some((c) => (c.removable || []).length)) roles.add('free');
    const supports = (r.steps || []).flatMap((s) => s.temporary_in_place || []);
    if (supports.some((t) => t.kind === 'hold')) roles.add('held');
    if ((this.scene.fixtures || []).length || supports.some((t) => t.kind === 'prop') ||
        (r.sequences || []).some((s) => (s.fixels || []).length)) roles.add('fixel');
    return roles;
  }

  // The legend: only the roles present, then the forces as drawn.
  fillLegend() {
    const row = (color, text) => $('div', {}, $('span', { class: 'sw', style: 'background:' + color }), text);
    const words = [['fixed', 'fixed'], ['judged', 'must stay put'], ['gripped', 'gripped (moved by the gripper)'],
                   ['carried', 'carried along'], ['tool', 'tool'], ['failed', 'moves: fails'], ['fixel', 'fixel or prop'],
                   ['held', 'held (a temporary hold)'], ['free', 'can leave alone along the cell\'s direction']];
    const present = this.rolesPresent();
    const el = this.legendEl;
    el.replaceChildren(...words.filter(([role]) => present.has(role)).map(([role, text]) => row(kColors[role], text)));
    if (this.data.kind === 'blocking') return;  // no forces
    const ramp = $('span', { class: 'sw', style: 'width:26px;background:linear-gradient(90deg,' + kColors.pairLight + ',' + kColors.pairDark + ')' });
    el.append($('div', {}, ramp, 'per pair of parts: the resultant of its contact forces, at its centre of pressure (darker: larger)'),
              row(kColors.normal, 'normal force at a contact point'), row(kColors.friction, 'friction force at a contact point'));
    this.scaleNote = $('div', { class: 'note', id: 'force-scale' });
    const gain = $('input', { type: 'range', min: '-3', max: '3', step: '0.1', value: '0', id: 'gain' });
    gain.addEventListener('input', () => {
      this.view.arrowGain = Math.pow(2, Number(gain.value));
      this.view.drawContacts();
      this.updateScaleNote();
    });
    const forces = $('input', { type: 'checkbox', checked: '' });
    forces.addEventListener('change', () => { this.view.showForces = forces.checked; this.view.drawContacts(); });
    const friction = $('input', { type: 'checkbox', checked: '' });
    friction.addEventListener('change', () => { this.view.showFriction = friction.checked; this.view.drawContacts(); });
    const points = $('input', { type: 'checkbox', id: 'every-point' });
    points.addEventListener('change', () => { this.view.forceMode = points.checked ? 'points' : 'pairs'; this.view.drawContacts(); });
    const idle = $('input', { type: 'checkbox', id: 'idle' });
    idle.addEventListener('change', () => { this.view.showIdle = idle.checked; this.view.drawContacts(); });
    el.append(this.scaleNote, $('label', { class: 'ctl' }, 'arrow length', gain),
              $('label', { class: 'ctl' }, forces, 'forces'), $('label', { class: 'ctl' }, friction, 'friction at contact points'),
              $('label', { class: 'ctl' }, points, 'every contact point (else one arrow per pair; click a part for its points)'),
              $('label', { class: 'ctl' }, idle, 'contacts that carry nothing'));
  }

  updateScaleNote() {
    const v = this.view;
    if (!this.scaleNote) return;  // a page without forces
    const len = v.forceReference * v.forceScale * v.arrowGain;
    this.scaleNote.textContent = 'An arrow ' + fmt(len, 3) + ' scene units long is ' + fmt(v.forceReference, 3) + ' ' + this.unit +
      ' (the largest normal force shown; the heaviest movable part weighs ' + fmt(this.scene.force_reference, 3) + ').';
  }

  // --- picking -------------------------------------------------------------
  bindPicking() {
    const canvas = this.view.renderer.domElement;
    let down = null;
    canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
    let pending = null;
    canvas.addEventListener('pointermove', (e) => {
      // One pick per frame, however fast the pointer moves.
      if (!pending) requestAnimationFrame(() => { this.hover(pending); pending = null; });
      pending = e;
    });
    canvas.addEventListener('pointerleave', () => { this.tip.style.display = 'none'; });
    canvas.addEventListener('click', (e) => {
      if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) > 4) return;  // a drag
      this.select(this.view.pick(e.clientX, e.clientY));
    });
  }

  // The numbers of what is under the pointer, in a tooltip.
  hover(e) {
    const hit = this.view.pick(e.clientX, e.clientY);
    const text = hit ? this.describe(hit) : '';
    this.tip.style.display = text ? 'block' : 'none';
    if (!text) return;
    const r = this.viewEl.getBoundingClientRect();
    this.tip.textContent = text;
    this.tip.style.left = Math.min(e.clientX - r.left + 14, r.width - 260) + 'px';
    this.tip.style.top = (e.clientY - r.top + 14) + 'px';
  }

  select(hit) {
    this.selected = hit;
    this.infoEl.textContent = hit ? this.describe(hit) : 'Hover or click a part or a contact point.';
    // A part selected: its contact points with their own arrows.
    const part = hit && hit.part !== undefined ? hit.part : -1;
    if (part !== this.view.selectedPart) {
      this.view.selectedPart = part;
      this.view.drawContacts();
    }
    if (hit && hit.contact !== undefined && this.chart) {
      const c = this.view.contacts;
      this.chart.select(c.a[hit.contact], c.b[hit.contact]);
    }
    if (hit && hit.pair !== undefined && this.chart) {
      const q = this.view.pairs[hit.pair];
      this.chart.select(q.pushed, q.pusher);
    }
  }

  describe(hit) {
    const name = (i) => (i >= 0 ? this.names[i] : 'the fixed world');
    if (hit.pair !== undefined) {
      const q = this.view.pairs[hit.pair];
      return [name(q.pusher) + ' pushes ' + name(q.pushed) + ' (' + q.contacts.length + ' contact' + (q.contacts.length === 1 ? '' : 's') + ')',
              'resultant on ' + name(q.pushed) + ': ' + vec(q.force.toArray()) + ', magnitude ' + fmt(q.magnitude) + ' ' + this.unit,
              'centre of pressure: ' + vec(q.point.toArray())].join('\n');
    }
    if (hit.part !== undefined) {
      const p = this.scene.parts[hit.part];
      const role = this.view.parts[hit.part].role || '';
      const lines = [p.name + (p.fixed ? ' (fixed)' : p.tool ? ' (tool)' : ''), 'role: ' + roleWords(role),
                     'mass: ' + fmt(p.mass), 'centroid: ' + vec(p.centroid)];
      const mo = (this.motions || []).find((m) => m.part === hit.part);
      if (mo) lines.push('motion: ' + motionWords(mo));
      return lines.join('\n');
    }
    const c = this.view.contacts, k = hit.contact;
    const ft = [c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]];
    const flags = c.flags[k];
    return [
      'contact ' + name(c.a[k]) + ' on ' + name(c.b[k]),
      'point: ' + vec(this.scene.dimension === 2 ? [c.p[3 * k], c.p[3 * k + 1]] : [c.p[3 * k], c.p[3 * k + 1], c.p[3 * k + 2]]),
      'normal (into ' + name(c.a[k]) + '): ' + vec(this.scene.dimension === 2 ? [c.n[3 * k], c.n[3 * k + 1]] : [c.n[3 * k], c.n[3 * k + 1], c.n[3 * k + 2]]),
      'normal force: ' + fmt(c.fn[k]) + ' ' + this.unit,
      'friction force: ' + fmt(Math.hypot(...ft)) + ' ' + this.unit,
      (flags & 1 ? 'breaks (opens)' : flags & 2 ? 'slides' : 'holds'),
    ].join('\n');
  }

  // --- the three kinds -----------------------------------------------------
  start() {
    if (this.data.kind === 'simulate') this.startSimulation();
    else if (this.data.kind === 'plan') this.startPlan();
    else if (this.data.kind === 'sequence') this.startSequence();
    else if (this.data.kind === 'margin') this.startMargin();
    else if (this.data.kind === 'blocking') this.startBlocking();
    else this.startCheck();
    this.fillLegend();
    this.updateScaleNote();
    // The first frame is drawn now, at the canvas' size with the side panel
    // and footer filled, before the page's load event (a screenshot taken
    // then has it); ready once a frame has been drawn by the browser's own
    // loop too (scripts and tests wait on it).
    this.view.resize();
    this.started = true;
    this.openingCamera();
    this.view.render();
    requestAnimationFrame(() => {
      this.view.render();
      requestAnimationFrame(() => {
        this.loadTime = performance.now();
        document.body.dataset.cairnReady = 'true';
      });
    });
  }

  // The parts in focus: those that fail, are gripped or held, can leave (a
  // blocking page's cell), or carry a fixel or prop, at the roles and
  // supports drawn now.
  focusParts() {
    const v = this.view, out = new Set();
    v.parts.forEach((p, i) => { if (['failed', 'gripped', 'held', 'free'].includes(p.role) && p.group.visible) out.add(i); });
    for (const f of v.fixelParts || []) if (f >= 0) out.add(f);
    return [...out];
  }

  // The opening camera (3-D): framed on the parts in focus and the parts
  // they touch, with the parts in front of them see-through. On a stable
  // check, the whole scene, with its most loaded joints named.
  openingCamera() {
    const focus = this.focusParts();
    this.updateLabels();
    if (!focus.length || this.scene.dimension !== 3) return;
    const c = this.view.contacts, near = new Set(focus);
    for (let k = 0; k < c.a.length; ++k) {
      if (focus.includes(c.a[k]) && c.b[k] >= 0) near.add(c.b[k]);
      if (focus.includes(c.b[k]) && c.a[k] >= 0) near.add(c.a[k]);
    }
    this.view.frameParts([...near]);
  }

  // Labels: every part that moves, is gripped or held, or carries a
  // support; on a stable check, the kMostLoadedJoints largest resultants.
  updateLabels() {
    const v = this.view, labels = [];
    const focus = this.focusParts();
    for (const i of focus) labels.push({ part: i, text: this.names[i], kind: v.parts[i].role === 'judged' ? 'fixel' : v.parts[i].role });
    v.setFocus(focus);
    if (!focus.length && this.data.kind === 'check' && this.result.stable)
      for (const j of this.mostLoadedJoints()) labels.push({ point: j.point.toArray(), kind: 'joint', text: j.text });
    v.setLabels(labels);
  }

  // The kMostLoadedJoints largest resultants per pair of parts drawn, each
  // at least a tenth of the scene from those before it: [{point, text}].
  mostLoadedJoints() {
    const name = (i) => (i >= 0 ? this.names[i] : 'the world');
    const out = [];
    for (const q of [...(this.view.pairs || [])].sort((x, y) => y.magnitude - x.magnitude)) {
      if (out.length >= kMostLoadedJoints || !(q.magnitude > 0)) break;
      if (out.some((j) => j.point.distanceTo(q.point) < 0.1 * this.scene.size)) continue;
      out.push({ point: q.point, text: name(q.pusher) + ' pushes ' + name(q.pushed) + ': ' + fmt(q.magnitude, 3) + ' ' + this.unit });
    }
    return out;
  }

  // Part i's role: `role` when i is in `set` (and not fixed), else fixed,
  // tool or must stay put.
  roleUnless(i, set, role) {
    const p = this.scene.parts[i];
    return p.fixed ? 'fixed' : set.has(i) ? role : p.tool ? 'tool' : 'judged';
  }

  motionsOfCheck() {
    return (this.result.parts || []).filter((p) => p.moving).map((p) => ({
      part: this.indexOf(p.name), motion: p.motion, pivot: p.pivot, axis: p.axis,
      linear: p.acceleration && p.acceleration.linear, angular: p.acceleration && p.acceleration.angular,
    }));
  }

  startCheck() {
    const r = this.result;
    const absent = (r.without || []).map(this.indexOf);
    const moving = new Set((r.moving || []).map(this.indexOf));
    this.motions = this.motionsOfCheck();
    this.view.setPoses([], absent);
    this.view.setRoles((i) => this.roleUnless(i, moving, 'failed'));
    this.view.setContacts(contactsFromReport(r.contacts, this.indexOf));
    this.view.setMotions(this.motions);
    const story = [];
    story.push((r.stable ? 'Stable' : 'Not stable') + (r.stability ? ' (' + r.stability + ')' : '') +
               (absent.length ? ' without ' + absent.map((i) => this.names[i]).join(', ') : '') + '.');
    // The parts that move, how and why, in the words of the text summary
    // (the command writes them: CheckStory).
    story.push(...(this.data.story || []).map((l) => l + '.'));
    story.push(...analysisWords(r));
    const joints = r.stable ? this.mostLoadedJoints() : [];
    if (joints.length) story.push('The most loaded joints (resultant per pair of parts): ' + joints.map((j) => j.text).join('; ') + '.');
    this.setStory(story);
    this.setSolverNotes(r.diagnostics);
    this.foot.append($('div', { class: 'note' }, (r.contacts || []).length + ' contacts · ' + this.names.length + ' parts'));
  }

  setStory(lines) {
    this.storyEl.replaceChildren(...lines.map((l) => $('li', {}, l)));
  }

  // What decided each component, folded away under the story.
  setSolverNotes(text) {
    if (!text) return;
    const notes = text.split(/;\s*(?=component \d|step \d)/).filter((t) => t.trim());
    this.storyEl.after($('details', { id: 'solver-notes' }, $('summary', {}, 'solver notes'),
                         $('ul', {}, ...notes.map((t) => $('li', {}, t.replace(/;\s*$/, ''))))));
  }

  // A simulation: frames (one per tick), a scrubber, play, the chart.
  startSimulation() {
    const frames = this.data.frames || [];
    const f = this.result.failure;
    this.failureFrame = f ? frames.findIndex((x) => x.step === f.step && x.tick === f.tick) : -1;
    this.failedParts = new Set(f ? (f.parts || []).map(this.indexOf) : []);
    this.failureMotions = f ? (f.motions || []).map((m) => ({
      part: this.indexOf(m.part), motion: m.motion, pivot: m.pivot,
      linear: m.velocity && m.velocity.linear, angular: m.velocity && m.velocity.angular,
      axis: m.axis,
    })) : [];
    const story = [];
    for (const s of this.result.steps || [])
      story.push('Step ' + (s.index + 1) + ': remove ' + (s.parts || []).join(', ') + ' (' + s.verdict + ', ' + (s.time_steps || 0) + ' time steps).');
    if (f && f.description) story.push(brief(f.description));
    // With --margin friction: the text summary's margin lines.
    story.push(...(this.data.story || []));
    this.setStory(story);
    this.setSolverNotes(this.result.diagnostics);

    const row = $('div', { class: 'row' });
    this.playBtn = $('button', { id: 'play' }, 'Play');
    this.playBtn.addEventListener('click', () => this.togglePlay());
    this.scrub = $('input', { type: 'range', id: 'scrub', min: '0', max: String(Math.max(frames.length - 1, 0)), step: '1', value: '0' });
    this.scrub.addEventListener('input', () => this.setFrame(Number(this.scrub.value)));
    const wrap = $('div', { id: 'scrub-wrap' }, this.scrub);
    if (this.failureFrame >= 0 && frames.length > 1) {
      const mark = $('div', { class: 'mark', id: 'failure-mark', title: 'failure' });
      mark.style.left = 'calc(' + (100 * this.failureFrame) / (frames.length - 1) + '% - 1px)';
      wrap.append(mark);
    }
    this.timeEl = $('span', { id: 'time' });
    row.append(this.playBtn, wrap, this.timeEl);
    this.chartCanvas = $('canvas', { id: 'chart' });
    // The chart's pair: any pair that touches at some tick (or click a
    // contact point).
    this.pairSelect = $('select', { id: 'pair' });
    const name = (i) => (i >= 0 ? this.names[i] : 'world');
    const pairs = new Map();
    for (const fr of frames)
      for (let k = 0; k < fr.contacts.a.length; ++k) {
        const a = fr.contacts.a[k], b = fr.contacts.b[k];
        const key = Math.min(a, b) + ',' + Math.max(a, b);
        if (!pairs.has(key)) pairs.set(key, [a, b]);
      }
    for (const [key, [a, b]] of [...pairs].sort((x, y) => name(x[1][0]).localeCompare(name(y[1][0])) || name(x[1][1]).localeCompare(name(y[1][1]))))
      this.pairSelect.append(new Option(name(a) + ' – ' + name(b), key));
    this.pairSelect.addEventListener('change', () => this.chart.select(...this.pairSelect.value.split(',').map(Number)));
    this.foot.append(row, $('label', { class: 'ctl' }, 'force between', this.pairSelect), this.chartCanvas);
    this.chart = new ForceChart(this.chartCanvas, frames, this.names, this.unit, this.failureFrame);
    this.chart.onSelect = (a, b) => { this.pairSelect.value = Math.min(a, b) + ',' + Math.max(a, b); };
    this.chart.select(...this.defaultPair(frames));
    this.setFrame(this.failureFrame >= 0 ? this.failureFrame : 0);
  }

  // The pair the chart opens on: the failing part's most loaded contact
  // pair at the failure, or the most loaded pair of all.
  defaultPair(frames) {
    let best = null, bestForce = -1;
    const scan = this.failureFrame >= 0 ? [frames[this.failureFrame]] : frames;
    for (const fr of scan) {
      const c = fr.contacts;
      const sums = new Map();
      for (let k = 0; k < c.a.length; ++k) {
        const key = c.a[k] + ',' + c.b[k];
        sums.set(key, (sums.get(key) || 0) + c.fn[k]);
      }
      for (const [key, s] of sums) {
        const [a, b] = key.split(',').map(Number);
        const w = s + (this.failedParts.has(a) || this.failedParts.has(b) ? 1e30 : 0);
        if (w > bestForce) { bestForce = w; best = [a, b]; }
      }
    }
    return best || [-1, -1];
  }

  setFrame(k) {
    const frames = this.data.frames || [];
    if (!frames.length) return;
    k = Math.max(0, Math.min(frames.length - 1, Math.round(k)));
    this.frame = k;
    const fr = frames[k];
    this.scrub.value = String(k);
    const roles = new Map(fr.roles || []);
    const failed = this.failureFrame >= 0 && k >= this.failureFrame;
    this.view.setPoses(fr.poses, fr.absent);
    this.view.setRoles((i) => {
      const p = this.scene.parts[i];
      if (p.fixed) return 'fixed';
      if (failed && this.failedParts.has(i)) return 'failed';
      const r = roles.get(i);
      return r || (p.tool ? 'tool' : 'judged');
    });
    this.view.setContacts(fr.contacts);
    this.motions = k === this.failureFrame ? this.failureMotions : [];
    this.view.setMotions(this.motions);
    this.timeEl.textContent = 't = ' + fmt(fr.time, 4) + ' s · step ' + (fr.step + 1) + ' · tick ' + fr.tick +
      (k === this.failureFrame ? ' · FAILS' : '');
    this.chart.setFrame(k);
    if (this.started) this.updateLabels();
    if (this.selected) this.infoEl.textContent = this.selected.part !== undefined ? this.describe(this.selected) : this.infoEl.textContent;
  }

  togglePlay() {
    const frames = this.data.frames || [];
    if (this.playing) {
      this.playing = false;
      this.playBtn.textContent = 'Play';
      return;
    }
    if (this.frame >= frames.length - 1) this.setFrame(0);
    this.playing = true;
    this.playBtn.textContent = 'Pause';
    // About four seconds for the whole simulation, at most 30 frames a second.
    const period = Math.max(1000 / 30, 4000 / Math.max(frames.length, 1));
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      if (now - last >= period) {
        last = now;
        if (this.frame >= frames.length - 1) { this.togglePlay(); return; }
        this.setFrame(this.frame + 1);
      }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  // A plan: the stable sequences; each plays step by step. A step's parts
  // slide along its path; the contacts and forces shown are the rest state
  // of the assembly that remains at the start of the step.
  startPlan() {
    const r = this.result;
    const seqs = r.sequences || [];
    const shown = this.data.plan ? this.data.plan.sequences_shown : seqs.length;
    const story = [seqs.length ? seqs.length + ' stable sequence' + (seqs.length === 1 ? '' : 's') + (r.complete === false ? ' (search stopped early)' : '') + '.' : 'No stable sequence: ' + (r.message || '')];
    const nonin = r.noninvertible_steps || [];
    if (nonin.length) story.push(nonin.length + ' removal' + (nonin.length === 1 ? ' is' : 's are') + ' stable one way only (non-invertible: marked ⚠).');
    if ((r.assembly_only_sequences || []).length) story.push(r.assembly_only_sequences.length + ' sequence(s) stable only as assembly.');
    this.setStory(story);
    const list = $('ul', { id: 'seqs' });
    this.seqItems = seqs.slice(0, shown).map((s, i) => {
      const warn = !s.invertible ? $('span', { class: 'warn', title: 'not invertible' }, ' ⚠') : '';
      const fix = s.fixels ? $('span', { class: 'warn', title: 'needs fixels' }, ' ✚' + s.fixels.length + ' fixel' + (s.fixels.length === 1 ? '' : 's')) : '';
      const li = $('li', {}, (i + 1) + '. ' + s.steps.map((st) => st.remove.join('+')).join(' → '), warn, fix);
      li.addEventListener('click', () => this.selectSequence(i));
      list.append(li);
      return li;
    });
    if (shown < seqs.length) list.append($('li', { class: 'note' }, '… and ' + (seqs.length - shown) + ' more (in the JSON)'));
    this.stepList = $('ol', { class: 'steps', id: 'steps' });
    this.extraSide.append($('h2', {}, 'Sequences'), list, $('h2', {}, 'Steps'), this.stepList);
    // The removals stable one way only (paper Section VIII): each plays as a
    // one-step sequence from the assembly it leaves.
    if (nonin.length) {
      const one = $('ul', { id: 'oneway' , class: 'steps' });
      this.onewayItems = nonin.map((n, i) => {
        const li = $('li', { title: n.failure || '' }, '⚠ ' + n.remove.join('+') + ' ' + n.label + ' from {' + n.remaining.join(', ') +
                     '}: disassembly ' + n.disassembly + ', assembly ' + n.assembly);
        li.style.cursor = 'pointer';
        li.addEventListener('click', () => this.selectOneWay(i));
        one.append(li);
        return li;
      });
      this.extraSide.append($('h2', {}, 'Stable one way only'), one);
    }
    const row = $('div', { class: 'row' });
    this.playBtn = $('button', { id: 'play' }, 'Play');
    this.playBtn.addEventListener('click', () => this.togglePlanPlay());
    this.scrub = $('input', { type: 'range', id: 'scrub', min: '0', max: '0', step: '0.01', value: '0' });
    this.scrub.addEventListener('input', () => this.setPlanTime(Number(this.scrub.value)));
    this.timeEl = $('span', { id: 'time' });
    row.append(this.playBtn, $('div', { id: 'scrub-wrap' }, this.scrub), this.timeEl);
    this.foot.append(row);
    this.view.setPoses([], []);
    this.view.setRoles((i) => (this.scene.parts[i].fixed ? 'fixed' : 'judged'));
    if (seqs.length) this.selectSequence(0);
  }

  selectOneWay(i) {
    const n = this.result.noninvertible_steps[i];
    const step = { remove: n.remove, path: n.path, support: n.support };
    const present = this.data.plan && this.data.plan.oneway ? this.data.plan.oneway[i] : null;
    this.showSequence({ steps: [step], checks: [n], present, fixels: n.fixels, invertible: false });
    this.seqItems.forEach((li) => li.classList.remove('on'));
    (this.onewayItems || []).forEach((li, k) => li.classList.toggle('now', k === i));
    this.infoEl.textContent = n.remove.join('+') + ' ' + n.label + ': disassembly ' + n.disassembly + ', assembly ' + n.assembly +
      (n.failure ? '\n' + n.failure : '');
  }

  selectSequence(i) {
    this.seqItems.forEach((li, k) => li.classList.toggle('on', k === i));
    (this.onewayItems || []).forEach((li) => li.classList.remove('now'));
    this.showSequence(this.result.sequences[i]);
  }

  // s: a sequence of the plan document (or a one-way removal as one); with
  // `present`, the indices of the parts present at its start (default: all).
  showSequence(s) {
    this.current = s;
    const nonin = this.result.noninvertible_steps || [];
    this.stepList.replaceChildren(...s.steps.map((st, k) => {
      const check = (s.checks || [])[k] || {};
      const one = nonin.some((n) => sameSet(n.remove, st.remove) && n.label === check.label);
      return $('li', {}, st.remove.join('+') + ' ' + (check.label || '') + (check.assembly && check.assembly !== check.disassembly ? ' ⚠ assembly ' + check.assembly : one ? ' ⚠' : ''));
    }));
    this.scrub.max = String(s.steps.length);
    this.view.setFixels([...(this.scene.fixtures || []), ...(s.fixels || []).map((f) => ({ ...f, part: this.indexOf(f.part) }))]);
    this.setPlanTime(0);
  }

  // t in [0, steps]: step floor(t), fraction t − floor(t) of its path.
  setPlanTime(t) {
    const s = this.current;
    if (!s) return;
    const n = s.steps.length;
    t = Math.max(0, Math.min(n, t));
    this.planTime = t;
    this.scrub.value = String(t);
    const k = Math.min(Math.floor(t), n - 1), frac = t >= n ? 1 : t - k;
    const gone = [];
    if (s.present) {
      const present = new Set(s.present);
      this.scene.parts.forEach((p, i) => { if (!present.has(i)) gone.push(i); });
    }
    for (let j = 0; j < k; ++j) for (const name of s.steps[j].remove) gone.push(this.indexOf(name));
    const step = s.steps[k];
    const moving = new Set(step.remove.map(this.indexOf));
    const done = t >= n;
    this.view.setPoses([], done ? [...gone, ...moving] : gone);
    const d = pathPoint(step, frac, this.scene.dimension);
    for (const i of moving) this.view.offsetPart(i, d);
    this.view.setRoles((i) => (this.scene.parts[i].fixed ? 'fixed' : moving.has(i) ? 'gripped' : 'judged'));
    const present = this.scene.parts.map((_, i) => i).filter((i) => !gone.includes(i) && !this.scene.parts[i].tool);
    const node = this.data.plan && this.data.plan.nodes ? this.data.plan.nodes[present.join(',')] : null;
    this.view.setContacts(node && frac === 0 ? node : emptyContacts());
    this.view.setMotions([]);
    [...this.stepList.children].forEach((li, j) => li.classList.toggle('now', j === k && !done));
    if (this.started) this.updateLabels();
    this.timeEl.textContent = done ? 'done' : 'step ' + (k + 1) + ' of ' + n + ': ' + step.remove.join('+') + (frac === 0 ? ' (at rest: forces shown)' : '');
  }

  togglePlanPlay() {
    if (this.playing) { this.playing = false; this.playBtn.textContent = 'Play'; return; }
    const s = this.current;
    if (!s) return;
    if (this.planTime >= s.steps.length) this.setPlanTime(0);
    this.playing = true;
    this.playBtn.textContent = 'Pause';
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      const t = this.planTime + (now - last) / 1500;  // 1.5 s a step
      last = now;
      if (t >= s.steps.length) { this.setPlanTime(s.steps.length); this.togglePlanPlay(); return; }
      this.setPlanTime(t);
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  // A build order (`cairn sequence`): the parts come in one a step along
  // their arrival directions; the supports in place are drawn where they go
  // in and gone where they come out (held parts in their colour with the
  // hold's force at the centroid, props as fixel arrows); at each state the
  // forces are its check's. The steps with the most supports are marked.
  startSequence() {
    const r = this.result, steps = r.steps || [], t = r.temporary || {};
    const states = (this.data.sequence && this.data.sequence.states) || [];
    this.states = states.map((c) => (c ? contactsFromReport(c, this.indexOf) : null));
    const story = [(r.complete ? 'Build order of ' + steps.length + ' parts' : 'No complete build order: ' + steps.length + ' parts placed') + '.'];
    const kinds = (t.kinds || []).join(' or ');
    story.push(t.max_in_place
      ? t.max_in_place + ' temporary support' + (t.max_in_place === 1 ? '' : 's') + ' (' + kinds + ') in place at once at most, ' +
        t.placements + ' put in in all; ' + (t.lower_bound > 0 ? 'no order needs fewer than ' + t.lower_bound + ' at once' : 'the lower bound proved is 0') +
        (t.lower_bound_reason ? ' (' + t.lower_bound_reason + ')' : '') + (t.optimal ? '; optimal.' : '.')
      : 'No temporary support needed' + (t.optimal ? ' (optimal).' : '.'));
    if (r.message) story.push(r.message);
    if (states.some((c) => c === null)) story.push('Forces are drawn for the first states only (the page keeps ' + this.data.sequence.max_contacts + ' contacts).');
    this.setStory(story);
    const peak = Math.max(0, ...steps.map((s) => s.temporary_in_place.length));
    this.stepList = $('ol', { class: 'steps', id: 'steps' });
    this.stepItems = steps.map((s, k) => {
      const words = ['place ' + s.place];
      for (const a of s.added) words.push(a.kind === 'hold' ? 'hold ' + a.part : 'prop under ' + a.part);
      for (const a of s.removed) words.push(a.kind === 'hold' ? 'release ' + a.part : 'take out the prop under ' + a.part);
      const most = peak > 0 && s.temporary_in_place.length === peak;
      const li = $('li', most ? { class: 'peak' } : {}, words.join('; '),
                   most ? $('span', { class: 'warn', title: 'the most supports in place at once' }, ' ▲' + peak) : '');
      li.style.cursor = 'pointer';
      li.addEventListener('click', () => this.setBuildTime(k + 1));
      this.stepList.append(li);
      return li;
    });
    this.extraSide.append($('h2', {}, 'Steps'), this.stepList);
    const row = $('div', { class: 'row' });
    this.playBtn = $('button', { id: 'play' }, 'Play');
    this.playBtn.addEventListener('click', () => this.toggleBuildPlay());
    this.scrub = $('input', { type: 'range', id: 'scrub', min: '0', max: String(steps.length), step: '0.01', value: '0' });
    this.scrub.addEventListener('input', () => this.setBuildTime(Number(this.scrub.value)));
    this.timeEl = $('span', { id: 'time' });
    row.append(this.playBtn, $('div', { id: 'scrub-wrap' }, this.scrub), this.timeEl);
    this.foot.append(row);
    this.setBuildTime(steps.length);
  }

  // The supports in place at build time t (SequenceSupports).
  buildSupports(t) {
    return sequenceSupports(this.result.steps || [], t);
  }

  // t in [0, steps]: an integer k is the state after k steps (its forces
  // drawn); between k and k + 1, part k + 1 comes in along its direction
  // (from half the scene away) under the supports in place before it and
  // those put in for it.
  setBuildTime(t) {
    const steps = this.result.steps || [], n = steps.length;
    t = Math.max(0, Math.min(n, t));
    this.buildTime = t;
    this.scrub.value = String(t);
    const k = Math.floor(t + 1e-9), frac = t - k;
    const arriving = frac > 1e-9 ? steps[k] : null;
    const placed = new Set(steps.slice(0, k).map((s) => this.indexOf(s.place)));
    if (arriving) placed.add(this.indexOf(arriving.place));
    const absent = this.scene.parts.map((p, i) => i).filter((i) => !this.scene.parts[i].fixed && !this.scene.parts[i].tool && !placed.has(i));
    this.view.setPoses([], absent);
    const supports = this.buildSupports(t);
    const held = new Set(supports.filter((s) => s.kind === 'hold').map((s) => this.indexOf(s.part)));
    const moving = arriving ? this.indexOf(arriving.place) : -1;
    if (arriving) {
      const d = pad3(arriving.direction), away = 0.5 * this.scene.size * (1 - frac);
      this.view.offsetPart(moving, new THREE.Vector3(-d[0] * away, -d[1] * away, -d[2] * away));
    }
    this.view.setRoles((i) => (this.scene.parts[i].fixed ? 'fixed' : i === moving ? 'gripped' : held.has(i) ? 'held' : 'judged'));
    const props = supports.filter((s) => s.kind === 'prop').map((s) => ({ ...s, part: this.indexOf(s.part) }));
    this.view.setFixels([...(this.scene.fixtures || []), ...props]);
    // At a state: its forces, and each hold's force as an arrow into the
    // held part's centroid.
    let c = emptyContacts();
    if (!arriving && k > 0 && this.states[k - 1]) {
      const s = this.states[k - 1];
      c = { a: [...s.a], b: [...s.b], p: [...s.p], n: [...s.n], fn: [...s.fn], ft: [...s.ft], flags: [...s.flags] };
      for (const h of steps[k - 1].temporary_in_place) {
        if (h.kind !== 'hold') continue;
        const f = pad3(h.force), size = Math.hypot(...f), p = pad3(h.point);
        if (!(size > 0)) continue;
        c.a.push(this.indexOf(h.part)); c.b.push(-1);
        c.p.push(...p); c.n.push(...f.map((x) => x / size)); c.fn.push(size); c.ft.push(0, 0, 0); c.flags.push(0);
      }
    }
    this.view.setContacts(c);
    this.view.setMotions([]);
    this.stepItems.forEach((li, j) => li.classList.toggle('now', arriving ? j === k : j === k - 1));
    if (this.started) this.updateLabels();
    this.timeEl.textContent = arriving ? 'step ' + (k + 1) + ' of ' + n + ': ' + arriving.place + ' comes in'
      : k === 0 ? 'the fixed parts' : 'after step ' + k + ' of ' + n + ' (' + supports.length + ' support' + (supports.length === 1 ? '' : 's') + ' in place; forces shown)';
  }

  toggleBuildPlay() {
    if (this.playing) { this.playing = false; this.playBtn.textContent = 'Play'; return; }
    const n = (this.result.steps || []).length;
    if (this.buildTime >= n) this.setBuildTime(0);
    this.playing = true;
    this.playBtn.textContent = 'Pause';
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing) return;
      const t = this.buildTime + (now - last) / Math.max(100, 8000 / Math.max(n, 1));  // about 8 s in all
      last = now;
      if (t >= n) { this.setBuildTime(n); this.toggleBuildPlay(); return; }
      this.setBuildTime(t);
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  // A margin (`cairn margin`): each component's equilibrium at its critical
  // value, with its forces, and the mechanism just past it (the parts that
  // move, drawn failing), played back and forth from the assembled pose.
  // The story is the text summary's lines.
  startMargin() {
    const m = this.result.margin || {}, certs = m.certificates || [];
    this.absent = (this.result.without || []).map(this.indexOf);
    this.setStory(this.data.story || []);
    // A tilt has two senses, each with its certificates: one at a time.
    const senses = [...new Set(certs.map((c) => c.sense || 'critical'))];
    this.showSense(senses[0]);
    const row = $('div', { class: 'row' });
    if (senses.length > 1) {
      const pick = $('select', { id: 'sense' }, ...senses.map((s) => new Option(s + ' sense', s)));
      pick.addEventListener('change', () => { this.showSense(pick.value); this.updateLabels(); });
      row.append(pick);
    }
    this.playBtn = $('button', { id: 'play' }, 'Pause');
    this.playBtn.addEventListener('click', () => this.toggleMechanism());
    this.scrub = $('input', { type: 'range', id: 'scrub', min: '0', max: '1', step: '0.01', value: '0' });
    this.scrub.addEventListener('input', () => { if (this.playing) this.toggleMechanism(); this.setMechanismPhase(Number(this.scrub.value)); });
    this.timeEl = $('span', { id: 'time' });
    row.append(this.playBtn, $('div', { id: 'scrub-wrap' }, this.scrub), this.timeEl);
    this.foot.append(row, $('div', { class: 'note' }, (this.mechanism.length
      ? 'The mechanism just past the critical value, exaggerated: its parts move ' + fmt(100 * kMechanismReach, 2) +
        ' % of the scene at the slider\'s end; the forces drawn are the equilibrium at the critical value.'
      : 'No mechanism: the forces drawn are the equilibrium at the critical value.') +
      (m.quantity === 'tilt' ? ' Drawn in the assembly\'s frame: at the critical tilt gravity is turned by the angle about the axis.' : '')));
    this.setMechanismPhase(0);
    if (this.mechanism.length) this.toggleMechanism();
  }

  // The certificates of one sense (a tilt's "positive" or "negative"; the
  // others have one, "critical"): their equilibria's forces and their
  // mechanisms' parts, drawn failing.
  showSense(sense) {
    const certs = ((this.result.margin || {}).certificates || []).filter((c) => (c.sense || 'critical') === sense);
    const contacts = emptyContacts();
    this.mechanism = [];
    for (const c of certs) {
      const eq = c.equilibrium && c.equilibrium.contacts ? c.equilibrium.contacts : [];
      const part = contactsFromReport(eq.map((k) => ({ ...k, parts: k.parts || [k.a, k.b] })), this.indexOf);
      for (const key of Object.keys(contacts)) contacts[key].push(...part[key]);
      if (c.mechanism && c.mechanism.found)
        for (const p of c.mechanism.parts || []) this.mechanism.push({ part: this.indexOf(p.part), motion: p.motion, linear: p.linear, angular: p.angular });
    }
    const moving = new Set(this.mechanism.map((x) => x.part));
    this.view.setPoses([], this.absent);
    this.view.setRoles((i) => this.roleUnless(i, moving, 'failed'));
    this.view.setContacts(contacts);
    this.motions = this.mechanism;
    this.view.setMotions(this.mechanism);
    if (this.scrub) this.setMechanismPhase(this.mechanismPhase || 0);
  }

  // s in [0, 1]: the mechanism's parts moved along their motion (a unit
  // twist: the fastest point moves 1 length unit per unit) by s times
  // kMechanismReach of the scene.
  setMechanismPhase(s) {
    this.mechanismPhase = s;
    this.scrub.value = String(s);
    const amount = s * kMechanismReach * this.scene.size;
    const poses = this.mechanism.map((x) => {
      const v = pad3(x.linear), w = new THREE.Vector3(...pad3(x.angular));
      const q = new THREE.Quaternion();
      if (w.lengthSq() > 0) q.setFromAxisAngle(w.clone().normalize(), w.length() * amount);
      return [x.part, v[0] * amount, v[1] * amount, v[2] * amount, q.x, q.y, q.z, q.w];
    });
    this.view.setPoses(poses, this.absent);
    this.timeEl.textContent = this.mechanism.length ? (s === 0 ? 'at the critical value: forces shown' : 'the mechanism, ' + fmt(100 * s, 2) + ' %') : '';
  }

  toggleMechanism() {
    if (this.playing) { this.playing = false; this.playBtn.textContent = 'Play'; return; }
    this.playing = true;
    this.playBtn.textContent = 'Pause';
    const t0 = performance.now() - Math.acos(1 - 2 * (this.mechanismPhase || 0)) / Math.PI * 1500;
    const tick = (now) => {
      if (!this.playing) return;
      // Out and back in three seconds.
      this.setMechanismPhase(0.5 - 0.5 * Math.cos((Math.PI * (now - t0)) / 1500));
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  // A blocking graph (`cairn blocking`): its cells listed as the text
  // summary lists them; the cell chosen is drawn: its direction as an arrow
  // on every part that can leave alone along it (drawn free), and what
  // blocks the others in its panel.
  startBlocking() {
    const cells = this.result.cells || [];
    const absent = (this.result.without || []).map(this.indexOf);
    this.view.setPoses([], absent);
    this.setStory(this.data.story || []);
    const list = $('ol', { class: 'steps', id: 'cells' });
    this.cellItems = cells.map((c, k) => {
      const li = $('li', {}, vec(c.direction) + ' leave: ' + ((c.removable || []).join(', ') || 'none'));
      li.style.cursor = 'pointer';
      li.addEventListener('click', () => this.selectCell(k));
      list.append(li);
      return li;
    });
    this.extraSide.append($('h2', {}, 'Cells (directions)'), list);
    const first = cells.findIndex((c) => (c.removable || []).length);
    if (cells.length) this.selectCell(Math.max(first, 0));
  }

  selectCell(k) {
    const c = this.result.cells[k];
    this.cell = k;
    const free = new Set((c.removable || []).map(this.indexOf));
    this.view.setRoles((i) => this.roleUnless(i, free, 'free'));
    const d = pad3(c.direction);
    this.view.setDirections([...free].map((i) => ({ part: i, direction: d })));
    this.cellItems.forEach((li, j) => li.classList.toggle('now', j === k));
    const blocked = (pairs) => {
      const by = new Map();
      for (const [a, b] of pairs || []) by.set(a, [...(by.get(a) || []), b]);
      return [...by].map(([a, bs]) => a + ' by ' + bs.join(', ')).join('; ') || 'nothing';
    };
    this.infoEl.textContent = 'direction ' + vec(c.direction) + (c.dimension !== undefined ? ' (a cell of dimension ' + c.dimension + ')' : '') +
      '\nleave alone: ' + ((c.removable || []).join(', ') || 'none') + '\nblocked (to infinity): ' + blocked(c.infinity) +
      '\nblocked at once (infinitesimally): ' + blocked(c.infinitesimal);
    if (this.started) this.updateLabels();
  }

  // --- the API for scripts and tests ----------------------------------------
  api() {
    const page = this;
    const loaded = () => (page.view.pairs || []).filter((q) => q.magnitude > 0);
    return {
      kind: this.data.kind,
      get frameCount() { return (page.data.frames || []).length; },
      get frame() { return page.frame; },
      get failureFrame() { return page.failureFrame; },
      setFrame: (k) => page.setFrame(k),
      setPlanTime: (t) => page.setPlanTime(t),
      setBuildTime: (t) => page.setBuildTime(t),
      selectCell: (k) => page.selectCell(k),
      // A margin page: pause the mechanism and set its phase (0: assembled).
      setMechanismPhase: (s) => { if (page.playing) page.toggleMechanism(); page.setMechanismPhase(s); },
      // The supports drawn: the parts coloured as held, and the props' points
      // (the fixel arrows beyond the scene's own fixtures).
      supportsDrawn: () => ({
        held: page.view.parts.map((p, i) => (p.role === 'held' ? page.names[i] : null)).filter((x) => x !== null).sort(),
        props: page.view.fixelArrows.heads.count - (page.scene.fixtures || []).length,
      }),
      selectSequence: (i) => page.selectSequence(i),
      selectOneWay: (i) => page.selectOneWay(i),
      selectPair: (a, b) => page.chart && page.chart.select(page.indexOf(a), page.indexOf(b)),
      partPose: (name) => page.view.partPosition(page.indexOf(name)),
      partVisible: (name) => page.view.parts[page.indexOf(name)].group.visible,
      partRole: (name) => page.view.parts[page.indexOf(name)].role,
      // Where a part is drawn on the canvas (CSS pixels from the canvas' top left).
      partScreen: (name) => page.view.screenOf(page.view.parts[page.indexOf(name)].group.position.toArray()),
      contactCount: () => page.view.contacts.a.length,
      // Force arrows drawn, and the pairs of parts with a contact force.
      arrowCount: () => page.view.arrowCount(),
      // Of the pairs with a force (pairCount), where pair j's resultant is
      // drawn (its centre of pressure), and its parts.
      pairScreen: (j) => page.view.screenOf(loaded()[j].point.toArray()),
      pairParts: (j) => [loaded()[j].pushed, loaded()[j].pusher].map((i) => (i >= 0 ? page.names[i] : null)),
      pairCount: () => loaded().length,
      setForceMode: (mode) => { page.view.forceMode = mode; page.view.drawContacts(); },
      // The names on the drawing, and the parts drawn see-through.
      labels: () => [...document.querySelectorAll('#view .label')].filter((e) => e.style.display !== 'none').map((e) => e.textContent),
      xrayParts: () => page.view.xrayParts().map((i) => page.names[i]),
      // The pixels where a part shows on the canvas (those that change when
      // it is hidden), and how many of them are in the failing colour's hue
      // (red well above green and blue).
      visiblePixels: (name) => page.view.visiblePixels(page.indexOf(name)),
      // Where contact k is drawn, and the parts it is between (by name).
      contactScreen: (k) => page.view.screenOf(page.view.contacts.p.slice(3 * k, 3 * k + 3)),
      contactParts: (k) => [page.view.contacts.a[k], page.view.contacts.b[k]].map((i) => (i >= 0 ? page.names[i] : null)),
      chartPair: () => (page.chart ? page.chart.pair.map((i) => (i >= 0 ? page.names[i] : null)) : null),
      chartMarkerX: () => (page.chart ? page.chart.markerX : null),
      loadTime: () => page.loadTime,
      // Draws n frames (poses and contacts of successive ticks when there
      // are any) and returns the mean time of one, in ms.
      frameTime: (n = 30) => {
        const frames = (page.data.frames || []).length;
        const t0 = performance.now();
        for (let k = 0; k < n; ++k) {
          if (frames) page.setFrame(k % frames);
          page.view.render();
        }
        page.view.renderer.getContext().finish();
        return (performance.now() - t0) / n;
      },
    };
  }
}

// The supports in place at build time t of a sequence's steps: after step
// k (t = k), its `temporary_in_place`; while step k + 1's part comes in,
// those and the ones put in for it on other parts.
function sequenceSupports(steps, t) {
  const k = Math.floor(t + 1e-9), frac = t - k;
  const after = k > 0 ? steps[k - 1].temporary_in_place : [];
  if (!(frac > 1e-9) || k >= steps.length) return after;
  const s = steps[k];
  return [...after, ...s.added.filter((a) => a.part !== s.place)];
}

function pathPoint(step, frac, dim) {
  if (step.direction) {
    const d = pad3(step.direction);
    return new THREE.Vector3(...d).multiplyScalar(frac * step.distance);
  }
  const pts = (step.path || [[0, 0, 0]]).map((p) => new THREE.Vector3(...pad3(p)));
  let total = 0;
  for (let k = 1; k < pts.length; ++k) total += pts[k].distanceTo(pts[k - 1]);
  let want = frac * total;
  for (let k = 1; k < pts.length; ++k) {
    const l = pts[k].distanceTo(pts[k - 1]);
    if (want <= l && l > 0) return pts[k - 1].clone().lerp(pts[k], want / l).sub(pts[0]);
    want -= l;
  }
  return pts[pts.length - 1].clone().sub(pts[0]);
}

// A failure's words up to its list of contacts (the list is in the panel
// of each contact, and in the JSON).
function brief(text) {
  const cut = text.indexOf('; contact ');
  return cut > 0 && text.length > 160 ? text.slice(0, cut) + '; …' : text;
}

function sameSet(a, b) {
  return a.length === b.length && a.every((x) => b.includes(x));
}

// A margin page's badge: the critical value, and whether it stands as given.
function marginVerdict(m) {
  const of = m.of === 'mu' ? 'μ*' : m.quantity === 'friction' ? 'k*' : m.quantity === 'tilt' ? 'tilt' : 'load';
  const crit = m.quantity === 'tilt' ? ' ' + (m.critical_deg || []).map((x) => (x === null ? 'none' : fmt(x, 4) + '°')).join(' / ')
    : m.critical === null || m.critical === undefined ? ' none' : ' = ' + fmt(m.critical, 4);
  return (m.stands_at_nominal ? 'stands' : 'does not stand') + ' · ' + of + crit;
}

function planVerdict(r) {
  return (r.sequences || []).length ? 'planned' : 'no stable sequence';
}

function roleWords(role) {
  return { fixed: 'fixed', judged: 'must stay put', gripped: 'gripped', carried: 'carried', tool: 'tool', failed: 'moves (fails)',
           free: 'can leave alone along the direction' }[role] || role;
}

function motionWords(m) {
  const lin = pad3(m.linear);
  if (m.motion === 'tips' && m.pivot) {
    const w = pad3(m.angular);
    const turn = m.pivot.length === 2 ? (w[2] < 0 ? ' clockwise' : ' counter-clockwise') : ' about the axis ' + vec(normalize(w));
    return 'tips about ' + vec(m.pivot) + turn;
  }
  const n = Math.hypot(...lin);
  return (m.motion || 'moves') + (n > 0 ? ' along ' + vec(lin.map((x) => x / n).slice(0, m.pivot && m.pivot.length === 2 ? 2 : 3)) : '');
}

function normalize(v) {
  const n = Math.hypot(...v);
  return n > 0 ? v.map((x) => x / n) : v;
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
else main();
