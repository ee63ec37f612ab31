// The drawing: parts, contact forces, motions and fixels in one three.js
// scene, in the page's data frame (Cairn's world frame, scene units).
//
// A part's geometry is given at its assembled pose in world coordinates; it
// is built relative to its assembled centroid c, so that a Cairn pose (a
// rotation R about c, then a translation t) is the mesh's transform:
//   mesh.position = c + t,  mesh.quaternion = R.
// 2-D scenes lie in z = 0 and are seen from +z through an orthographic
// camera; 3-D scenes through a perspective camera whose "up" is against
// gravity.

import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { kColors } from './style.js';

const kUp = new THREE.Vector3(0, 0, 1);
// The opacity of a part drawn see-through because it hides a part in focus.
const kXrayOpacity = 0.16;
// A part in focus is sampled at its centroid and at most this many of its
// mesh's vertices to find the parts in front of it.
const kXraySamples = 24;

// Contacts in the page's compact form: flat arrays, one entry (or triple) per
// contact. `a`, `b` are part indices (-1: the fixed world, e.g. a fixel).
export function emptyContacts() {
  return { a: [], b: [], p: [], n: [], fn: [], ft: [], flags: [] };
}

// The contacts of a check document (its `contacts` list) in compact form.
export function contactsFromReport(list, indexOf) {
  const c = emptyContacts();
  for (const k of list || []) {
    c.a.push(indexOf(k.parts[0]));
    c.b.push(indexOf(k.parts[1]));
    const p = k.point, n = k.normal;
    c.p.push(p[0], p[1], p.length > 2 ? p[2] : 0);
    c.n.push(n[0], n[1], n.length > 2 ? n[2] : 0);
    c.fn.push(k.normal_force || 0);
    const f = k.friction_force;
    if (Array.isArray(f)) c.ft.push(f[0], f[1], f.length > 2 ? f[2] : 0);
    else c.ft.push(-n[1] * (f || 0), n[0] * (f || 0), 0);  // 2-D: along t = z × n
    c.flags.push((k.breaks ? 1 : 0) | (k.slides ? 2 : 0));
  }
  return c;
}

function partGeometry(part, dim) {
  const c = new THREE.Vector3(...part.centroid);
  if (dim === 2) {
    const shape = new THREE.Shape(part.outline.map(([x, y]) => new THREE.Vector2(x - c.x, y - c.y)));
    const fill = new THREE.ShapeGeometry(shape);
    const pts = part.outline.map(([x, y]) => new THREE.Vector3(x - c.x, y - c.y, 0.001));
    const edges = new THREE.BufferGeometry().setFromPoints([...pts, pts[0]]);
    return { fill, edges, loop: true };
  }
  // The vertices `indices` lists, one after the other, relative to c: the
  // triangles (not indexed: flat faces) and the edges' segments.
  const gather = (indices) => {
    const v = part.vertices, pos = new Float32Array(indices.length * 3);
    indices.forEach((i, k) => {
      pos[3 * k] = v[3 * i] - c.x;
      pos[3 * k + 1] = v[3 * i + 1] - c.y;
      pos[3 * k + 2] = v[3 * i + 2] - c.z;
    });
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    return g;
  };
  const fill = gather(part.triangles);
  fill.computeVertexNormals();
  const edges = gather(part.edges || []);
  return { fill, edges, loop: false };
}

// Arrows as line segments plus instanced cone heads: thousands of contacts
// stay one draw call each. They are drawn over the parts (no depth test): a
// force between two faces is inside the solids.
class ArrowSet {
  // With `colored`, each arrow takes its own colour (set's third element).
  constructor(color, capacity, headSize, colored = false) {
    this.color = color;
    this.headSize = headSize;
    this.colored = colored;
    const over = { color: colored ? 0xffffff : color, depthTest: false, transparent: true, opacity: 0.9 };
    this.lines = new THREE.LineSegments(new THREE.BufferGeometry(),
                                        new THREE.LineBasicMaterial({ ...over, vertexColors: colored }));
    this.lines.renderOrder = 20;
    const cone = new THREE.ConeGeometry(0.35, 1, 10).translate(0, -0.5, 0);
    this.heads = new THREE.InstancedMesh(cone, new THREE.MeshBasicMaterial(over), capacity);
    this.heads.renderOrder = 20;
    this.heads.count = 0;
    this.group = new THREE.Group();
    this.group.add(this.lines, this.heads);
  }
  // [[from Vector3, to Vector3, colour (THREE.Color, when colored), head scale], ...]
  set(arrows) {
    const pos = new Float32Array(arrows.length * 6);
    const rgb = this.colored ? new Float32Array(arrows.length * 6) : null;
    const m = new THREE.Matrix4(), q = new THREE.Quaternion(), d = new THREE.Vector3();
    const yAxis = new THREE.Vector3(0, 1, 0);
    if (arrows.length > this.heads.instanceMatrix.count) {
      const cap = Math.max(arrows.length, 2 * this.heads.instanceMatrix.count);
      this.group.remove(this.heads);
      this.heads.dispose();
      this.heads = new THREE.InstancedMesh(this.heads.geometry, this.heads.material, cap);
      this.heads.renderOrder = 20;
      this.group.add(this.heads);
    }
    arrows.forEach(([from, to, color, scale = 1], k) => {
      from.toArray(pos, 6 * k);
      to.toArray(pos, 6 * k + 3);
      d.subVectors(to, from);
      const len = d.length();
      const h = Math.min(this.headSize * scale, 0.45 * len);
      q.setFromUnitVectors(yAxis, len > 0 ? d.divideScalar(len) : yAxis);
      m.compose(to, q, new THREE.Vector3(h, h, h));
      this.heads.setMatrixAt(k, m);
      if (rgb) {
        color.toArray(rgb, 6 * k);
        color.toArray(rgb, 6 * k + 3);
        this.heads.setColorAt(k, color);
      }
    });
    this.lines.geometry.dispose();
    this.lines.geometry = new THREE.BufferGeometry();
    this.lines.geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    if (rgb) this.lines.geometry.setAttribute('color', new THREE.BufferAttribute(rgb, 3));
    if (rgb && this.heads.instanceColor) this.heads.instanceColor.needsUpdate = true;
    this.heads.count = arrows.length;
    this.heads.instanceMatrix.needsUpdate = true;
    this.heads.computeBoundingSphere();
  }
}

export class SceneView {
  constructor(container, scene) {
    this.data = scene;
    this.dim = scene.dimension;
    this.size = scene.size || 1;
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(0xf6f5f2);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.forceScale = 1;     // scene length per force unit (set by setForceReference)
    this.arrowGain = 1;      // the user's slider
    this.showForces = true;
    this.showFriction = true;
    this.forceMode = 'pairs';  // drawContacts
    this.showIdle = false;
    this.selectedPart = -1;
    this.needsRender = true;
    this.buildCamera();
    this.buildLights();
    this.buildParts();
    this.buildOverlays();
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  // --- camera and lights ---------------------------------------------------
  buildCamera() {
    const box = new THREE.Box3();
    for (const p of this.data.parts) {
      const pts = this.dim === 2 ? p.outline.map(([x, y]) => [x, y, 0]) : null;
      if (pts) pts.forEach((q) => box.expandByPoint(new THREE.Vector3(...q)));
      else for (let k = 0; k < p.vertices.length; k += 3)
        box.expandByPoint(new THREE.Vector3(p.vertices[k], p.vertices[k + 1], p.vertices[k + 2]));
    }
    if (box.isEmpty()) box.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
    this.box = box;
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-9);
    this.radius = radius;
    if (this.dim === 2) {
      this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, -10 * radius, 10 * radius);
      this.camera.position.set(center.x, center.y, 5 * radius);
      this.camera.up.set(0, 1, 0);
    } else {
      const g = new THREE.Vector3(...(this.data.gravity || [0, 0, -9.81]));
      const up = g.lengthSq() > 0 ? g.clone().negate().normalize() : kUp.clone();
      this.camera = new THREE.PerspectiveCamera(35, 1, radius / 100, radius * 100);
      this.camera.up.copy(up);
      // A three-quarter view from the side, slightly above.
      const side = Math.abs(up.z) > 0.9 ? new THREE.Vector3(1, -1.6, 0) : new THREE.Vector3(1, 0, 1.6);
      side.addScaledVector(up, -side.dot(up)).normalize();
      const eye = side.multiplyScalar(2.9 * radius).addScaledVector(up, 1.3 * radius);
      this.camera.position.copy(center).add(eye);
    }
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.copy(center);
    if (this.dim === 2) {
      this.controls.enableRotate = false;
      this.controls.screenSpacePanning = true;
      this.controls.mouseButtons = { LEFT: THREE.MOUSE.PAN, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.PAN };
    }
    this.controls.addEventListener('change', () => this.requestRender());
    this.controls.update();
  }

  buildLights() {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8d877c, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.copy(this.camera.up).multiplyScalar(3).add(new THREE.Vector3(1, 0.6, 0.3)).multiplyScalar(this.radius);
    this.scene.add(sun);
  }

  resize() {
    const w = Math.max(this.container.clientWidth, 10), h = Math.max(this.container.clientHeight, 10);
    this.renderer.setSize(w, h, false);
    if (this.dim === 2) {
      // The scene's box with a margin, whatever the window's shape.
      const size = this.box.getSize(new THREE.Vector3());
      const half = Math.max(size.x / 2, (size.y / 2) * (w / h), 1e-9) * 1.25;
      const c = this.camera;
      c.left = -half;
      c.right = half;
      c.top = (half * h) / w;
      c.bottom = (-half * h) / w;
    } else {
      this.camera.aspect = w / h;
    }
    this.camera.updateProjectionMatrix();
    // A new size clears the canvas: draw again now, not at the next frame,
    // so that no frame (and no screenshot) shows it empty.
    this.render();
  }

  // --- parts ---------------------------------------------------------------
  buildParts() {
    this.parts = this.data.parts.map((p, i) => {
      const { fill, edges, loop } = partGeometry(p, this.dim);
      // 2-D: flat colours exactly as the legend's; 3-D: lit, flat-shaded faces.
      const common = { color: kColors.judged, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
      const material = this.dim === 2
        ? new THREE.MeshBasicMaterial({ ...common, side: THREE.DoubleSide })
        : new THREE.MeshStandardMaterial({ ...common, roughness: 0.85, metalness: 0.0, flatShading: true });
      const mesh = new THREE.Mesh(fill, material);
      const lineMat = new THREE.LineBasicMaterial({ color: 0x2b2b2b, transparent: true, opacity: 0.55 });
      const outline = loop ? new THREE.Line(edges, lineMat) : new THREE.LineSegments(edges, lineMat);
      const group = new THREE.Group();
      group.add(mesh, outline);
      group.userData = { part: i };
      mesh.userData = { part: i };
      group.position.set(...p.centroid);
      this.scene.add(group);
      return { group, mesh, material, centroid: new THREE.Vector3(...p.centroid) };
    });
  }

  // Poses: [[index, tx, ty, tz, qx, qy, qz, qw], ...] for the parts away from
  // their assembled pose; every other present part is assembled.
  setPoses(poses, absent) {
    const gone = new Set(absent || []);
    this.parts.forEach((p, i) => {
      p.group.position.copy(p.centroid);
      p.group.quaternion.identity();
      p.group.visible = !gone.has(i);
    });
    for (const [i, tx, ty, tz, qx, qy, qz, qw] of poses || []) {
      const p = this.parts[i];
      p.group.position.set(p.centroid.x + tx, p.centroid.y + ty, p.centroid.z + tz);
      p.group.quaternion.set(qx, qy, qz, qw);
    }
    if (this.focus && this.focus.size) this.xrayStale = true;
    this.requestRender();
  }

  // Translates part i by d from where setPoses put it (plan playback).
  offsetPart(i, d) {
    this.parts[i].group.position.add(d);
    this.requestRender();
  }

  setRoles(roleOf) {  // roleOf(i) -> key of kColors
    this.parts.forEach((p, i) => {
      p.role = roleOf(i);
      this.applyLook(p);
    });
    this.requestRender();
  }

  // A part's colour by its role; see-through when it hides a part in focus
  // (x-ray: setFocus) or is a ghost.
  applyLook(p) {
    p.material.color.set(kColors[p.role] || kColors.judged);
    const see = p.role === 'ghost' || p.xray;
    // An opaque material's shader forces alpha to 1: a change of
    // transparency needs the shader built again.
    if (p.material.transparent !== see) p.material.needsUpdate = true;
    p.material.transparent = see;
    p.material.opacity = p.role === 'ghost' ? 0.25 : p.xray ? kXrayOpacity : 1;
    p.material.depthWrite = !p.xray;
    p.group.children[1].material.opacity = p.xray ? 0.2 : 0.55;
  }

  partPosition(i) {
    const p = this.parts[i].group;
    return [p.position.x, p.position.y, p.position.z, p.quaternion.x, p.quaternion.y, p.quaternion.z, p.quaternion.w];
  }

  // --- contacts, motions, fixels -------------------------------------------
  buildOverlays() {
    // Marks scale with the parts, not only the scene: a vault of 399 small
    // blocks keeps its contact points apart.
    const diagonals = this.parts.map((p) => new THREE.Box3().setFromObject(p.mesh).getSize(new THREE.Vector3()).length()).sort((x, y) => x - y);
    const typical = diagonals.length ? diagonals[Math.floor(diagonals.length / 2)] : this.size;
    this.mark = Math.min(0.006 * this.size, 0.02 * typical);
    const head = Math.min(this.size * 0.018, 0.08 * typical);
    this.normals = new ArrowSet(kColors.normal, 64, head);
    this.resultants = new ArrowSet(kColors.pairDark, 64, head, true);
    this.frictions = new ArrowSet(kColors.friction, 64, head);
    const dot = new THREE.SphereGeometry(1, 8, 6);
    this.dots = new THREE.InstancedMesh(dot, new THREE.MeshBasicMaterial({ color: 0x1d1f23 }), 64);
    this.dots.count = 0;
    this.motionArrows = new ArrowSet(kColors.failed, 8, head * 1.6);
    this.fixelArrows = new ArrowSet(kColors.fixel, 8, head * 1.3);
    this.directionArrows = new ArrowSet(kColors.free, 8, head * 1.6);
    this.motionMarks = new THREE.Group();
    this.overlay = new THREE.Group();
    this.overlay.add(this.resultants.group, this.normals.group, this.frictions.group, this.dots, this.motionArrows.group,
                     this.fixelArrows.group, this.directionArrows.group, this.motionMarks);
    this.overlay.renderOrder = 10;
    this.scene.add(this.overlay);
    this.contacts = emptyContacts();
  }

  // Arrow length = force × forceScale × gain; forceScale makes `reference`
  // force units as long as `fraction` of the scene.
  setForceReference(reference, fraction = 0.12) {
    this.forceReference = reference > 0 ? reference : 1;
    this.forceScale = (fraction * this.size) / this.forceReference;
  }

  setContacts(c) {
    this.contacts = c || emptyContacts();
    this.drawContacts();
  }

  // Per pair of parts, the resultant of its contacts' forces on the part
  // pushed (a movable part before a fixed one, the world never, as the text
  // summary says it), applied at the centre of pressure (the contact points
  // weighted by their normal forces). `contacts`: the pair's contact indices.
  pairResultants() {
    const c = this.contacts, n = this.data.parts.length;
    const rank = (i) => (i < 0 ? Infinity : this.data.parts[i].fixed ? n + i : i);
    const pairs = new Map();
    for (let k = 0; k < c.a.length; ++k) {
      const aFirst = rank(c.a[k]) < rank(c.b[k]);
      const pushed = aFirst ? c.a[k] : c.b[k], pusher = aFirst ? c.b[k] : c.a[k];
      const key = pushed + ',' + pusher;
      let q = pairs.get(key);
      if (!q) pairs.set(key, (q = { pushed, pusher, force: new THREE.Vector3(), weighted: new THREE.Vector3(),
                                    mean: new THREE.Vector3(), fn: 0, contacts: [] }));
      const p = new THREE.Vector3(c.p[3 * k], c.p[3 * k + 1], c.p[3 * k + 2]);
      const f = new THREE.Vector3(c.n[3 * k], c.n[3 * k + 1], c.n[3 * k + 2]).multiplyScalar(c.fn[k])
        .add(new THREE.Vector3(c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]));
      q.force.addScaledVector(f, aFirst ? 1 : -1);
      q.weighted.addScaledVector(p, Math.max(c.fn[k], 0));
      q.mean.add(p);
      q.fn += Math.max(c.fn[k], 0);
      q.contacts.push(k);
    }
    return [...pairs.values()].map((q) => ({
      pushed: q.pushed, pusher: q.pusher, force: q.force, magnitude: q.force.length(), contacts: q.contacts,
      point: q.fn > 0 ? q.weighted.divideScalar(q.fn) : q.mean.divideScalar(q.contacts.length),
    }));
  }

  // What is drawn of the contacts (forceMode):
  //  - 'pairs' (the default): per pair of parts one arrow, the resultant at
  //    its centre of pressure, coloured by magnitude (light to dark); the
  //    selected part's contact points with their own arrows;
  //  - 'points': every contact point with its normal and friction arrows.
  // Contacts that carry nothing are hidden unless showIdle.
  drawContacts() {
    const c = this.contacts, count = c.a.length;
    const s = this.forceScale * this.arrowGain;
    const lift = this.dim === 2 ? 0.002 * this.size : 0;
    const tiny = 1e-9 * this.forceReference;
    const carries = (k) => c.fn[k] > tiny || Math.hypot(c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]) > tiny;
    const at = (k) => new THREE.Vector3(c.p[3 * k], c.p[3 * k + 1], c.p[3 * k + 2] + lift);
    // Each force is drawn as the push it is: an arrow ending at the contact
    // point, pointing into the part it acts on (a).
    const normals = [], frictions = [], resultants = [];
    this.dotItems = [];
    const point = (k) => {
      if (!carries(k) && !this.showIdle) return;
      const p = at(k);
      this.dotItems.push({ contact: k, p });
      if (!this.showForces) return;
      const fn = c.fn[k];
      if (fn * s > 1e-6 * this.size) {
        const n = new THREE.Vector3(c.n[3 * k], c.n[3 * k + 1], c.n[3 * k + 2]);
        normals.push([p.clone().addScaledVector(n, -fn * s), p]);
      }
      const ft = new THREE.Vector3(c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]);
      if (this.showFriction && ft.length() * s > 1e-6 * this.size) frictions.push([p.clone().addScaledVector(ft, -s), p]);
    };
    this.pairs = this.pairResultants();
    if (this.forceMode === 'points') {
      for (let k = 0; k < count; ++k) point(k);
    } else {
      const largest = Math.max(0, ...this.pairs.map((q) => q.magnitude));
      this.pairs.forEach((q, j) => {
        if (!(q.magnitude > tiny) && !this.showIdle) return;
        const p = q.point.clone();
        p.z += lift;
        this.dotItems.push({ pair: j, p });
        if (!this.showForces || !(q.magnitude * s > 1e-6 * this.size)) return;
        const t = largest > 0 ? q.magnitude / largest : 0;
        const color = new THREE.Color(kColors.pairLight).lerp(new THREE.Color(kColors.pairDark), Math.sqrt(t));
        resultants.push([p.clone().addScaledVector(q.force, -s), p, color, 0.6 + 0.8 * Math.sqrt(t)]);
      });
      const sel = this.selectedPart;
      if (sel >= 0) for (let k = 0; k < count; ++k) if (c.a[k] === sel || c.b[k] === sel) point(k);
    }
    const dots = this.dotItems.length;
    if (dots > this.dots.instanceMatrix.count) {
      this.overlay.remove(this.dots);
      this.dots.dispose();
      this.dots = new THREE.InstancedMesh(this.dots.geometry, this.dots.material, Math.max(dots, 2 * this.dots.instanceMatrix.count));
      this.overlay.add(this.dots);
    }
    const m = new THREE.Matrix4(), r = this.mark;
    this.dotItems.forEach((d, k) => {
      m.makeScale(r, r, r).setPosition(d.p);
      this.dots.setMatrixAt(k, m);
    });
    this.dots.count = dots;
    this.dots.instanceMatrix.needsUpdate = true;
    this.dots.computeBoundingSphere();
    this.normals.set(normals);
    this.frictions.set(frictions);
    this.resultants.set(resultants);
    this.requestRender();
  }

  // The number of force arrows drawn (resultants, normal and friction arrows).
  arrowCount() {
    return this.resultants.heads.count + this.normals.heads.count + this.frictions.heads.count;
  }

  // motions: [{part, motion: "tips"|"slides"|"falls"|..., pivot, linear, angular}]
  setMotions(motions) {
    this.motionMarks.clear();
    const arrows = [];
    for (const mo of motions || []) {
      const part = this.parts[mo.part];
      if (!part) continue;
      const at = part.group.position.clone();
      const lin = new THREE.Vector3(...pad3(mo.linear));
      const ang = new THREE.Vector3(...pad3(mo.angular));
      if (mo.motion === 'tips' && mo.pivot) {
        // The pivot: a ring about the axis of the tip (2-D: about z), drawn
        // over the parts; in 3-D the axis itself, a rod through the pivot.
        const pivot = new THREE.Vector3(...pad3(mo.pivot));
        const over = new THREE.MeshBasicMaterial({ color: kColors.pivot, depthTest: false, transparent: true, opacity: 0.85 });
        const r = this.dim === 2 ? this.size * 0.02 : this.size * 0.03;
        const ring = new THREE.Mesh(new THREE.TorusGeometry(r, r * 0.18, 8, 32), over);
        ring.position.copy(pivot);
        const axis = mo.axis ? new THREE.Vector3(...pad3(mo.axis)).normalize()
          : ang.lengthSq() > 0 ? ang.clone().normalize() : kUp.clone();
        ring.quaternion.setFromUnitVectors(kUp, axis);
        ring.renderOrder = 30;
        this.motionMarks.add(ring);
        if (this.dim === 3) {
          const rod = new THREE.Mesh(new THREE.CylinderGeometry(r * 0.12, r * 0.12, this.size * 0.25, 8), over);
          rod.position.copy(pivot);
          rod.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis);
          rod.renderOrder = 30;
          this.motionMarks.add(rod);
        }
        // The centroid's direction of motion: ω × (c − pivot).
        const v = new THREE.Vector3().crossVectors(ang, at.clone().sub(pivot));
        if (v.lengthSq() > 0) arrows.push([at, at.clone().addScaledVector(v.normalize(), this.size * 0.1)]);
      } else if (lin.lengthSq() > 0) {
        arrows.push([at, at.clone().addScaledVector(lin.normalize(), this.size * 0.1)]);
      }
    }
    this.motionArrows.set(arrows);
    this.requestRender();
  }

  // Directions a part can leave along ([{part, direction}]): an arrow from
  // its centroid, in the colour of the parts that can leave.
  setDirections(list) {
    this.directionArrows.set((list || []).map(({ part, direction }) => {
      const at = this.parts[part].group.position.clone();
      return [at, at.clone().addScaledVector(new THREE.Vector3(...direction).normalize(), 0.12 * this.size)];
    }));
    this.requestRender();
  }

  setFixels(fixels) {  // [{part, point, normal}]: arrows pushing into the part
    this.fixelParts = (fixels || []).map((f) => (typeof f.part === 'number' ? f.part : -1));
    const arrows = (fixels || []).map((f) => {
      const p = new THREE.Vector3(...pad3(f.point)), n = new THREE.Vector3(...pad3(f.normal)).normalize();
      return [p.clone().addScaledVector(n, -0.08 * this.size), p];
    });
    this.fixelArrows.set(arrows);
    this.requestRender();
  }

  // --- labels, focus and x-ray ----------------------------------------------
  // Names drawn over the canvas, each at a part's centroid ({part, text,
  // kind}) or at a point ({point: [x, y, z], text, kind}); `kind` styles it.
  setLabels(labels) {
    if (!this.labelLayer) {
      this.labelLayer = document.createElement('div');
      this.labelLayer.className = 'labels';
      this.container.append(this.labelLayer);
    }
    this.labels = labels.map((l) => {
      const el = document.createElement('div');
      el.className = 'label' + (l.kind ? ' ' + l.kind : '');
      el.textContent = l.text;
      return { ...l, el };
    });
    this.labelLayer.replaceChildren(...this.labels.map((l) => l.el));
    // Their sizes, once (reading them at every frame would lay the page out
    // at every frame).
    for (const l of this.labels) {
      l.el.style.display = 'block';
      l.w = l.el.offsetWidth;
      l.h = l.el.offsetHeight;
    }
    this.placeLabels();
    this.requestRender();
  }

  // Each label above its point, moved down past the labels placed before it
  // where they would overlap, and left out (named on hover) where it would
  // still overlap one: a label drawn is a label read.
  placeLabels() {
    if (!(this.labels || []).length) return;
    const placed = [];
    const r = this.renderer.domElement, width = r.clientWidth, height = r.clientHeight;
    for (const l of this.labels) {
      const part = l.part !== undefined ? this.parts[l.part] : null;
      if (part && !part.group.visible) { l.el.style.display = 'none'; continue; }
      const p = part ? part.group.position : new THREE.Vector3(...pad3(l.point));
      const v = p.clone().project(this.camera);
      if (v.z > 1 || Math.abs(v.x) > 1.2 || Math.abs(v.y) > 1.2) { l.el.style.display = 'none'; continue; }
      l.el.style.display = 'block';
      const { w, h } = l;
      const x = ((v.x + 1) / 2) * width - w / 2;
      let y = ((1 - v.y) / 2) * height - 1.35 * h;
      const overlaps = () => placed.some((q) => Math.abs(q.x - x - w / 2) < (q.w + w) / 2 + 2 && Math.abs(q.y - y) < h + 1);
      for (let k = 0; k < 2 && overlaps(); ++k) y += h + 2;
      if (overlaps()) { l.el.style.display = 'none'; continue; }
      placed.push({ x: x + w / 2, y, w });
      l.el.style.transform = 'translate(' + x.toFixed(1) + 'px,' + y.toFixed(1) + 'px)';
    }
  }

  // Turns the 3-D camera, keeping its direction, to frame the parts
  // `indices` (at their poses now), with a margin.
  frameParts(indices) {
    if (this.dim !== 3) return;
    const box = new THREE.Box3();
    for (const i of indices) if (this.parts[i] && this.parts[i].group.visible) box.expandByObject(this.parts[i].mesh);
    if (box.isEmpty()) return;
    const center = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.02 * this.radius);
    const half = THREE.MathUtils.degToRad(this.camera.fov / 2);
    const fit = Math.min(Math.tan(half), Math.tan(half) * this.camera.aspect);
    const dir = this.camera.position.clone().sub(this.controls.target).normalize();
    this.controls.target.copy(center);
    this.camera.position.copy(center).addScaledVector(dir, (1.15 * radius) / Math.sin(Math.atan(fit)));
    this.controls.update();
    this.xrayStale = true;
  }

  // The parts in focus (those that fail, are gripped or held, can leave,
  // carry a support): every other part in front of one of them, as the
  // camera sees it, is drawn see-through, found again before the next frame
  // whenever the focus changes, the camera stops or the parts move (once a
  // frame however many of those happen).
  setFocus(indices) {
    this.focus = new Set(indices);
    if (!this.xrayBound) {
      this.xrayBound = true;
      this.controls.addEventListener('end', () => {
        this.xrayStale = true;
        this.requestRender();
      });
    }
    this.xrayStale = true;
    this.requestRender();
  }

  updateXray() {
    this.xrayStale = false;
    const xray = new Set();
    if (this.dim === 3 && this.focus && this.focus.size) {
      this.scene.updateMatrixWorld(true);
      const others = this.parts.filter((p, i) => p.group.visible && !this.focus.has(i)).map((p) => p.mesh);
      const eye = this.camera.position, ray = new THREE.Raycaster(), v = new THREE.Vector3();
      for (const i of this.focus) {
        const part = this.parts[i];
        if (!part || !part.group.visible) continue;
        const pos = part.mesh.geometry.attributes.position;
        const step = Math.max(1, Math.floor(pos.count / kXraySamples));
        const samples = [part.group.position.clone()];
        for (let k = 0; k < pos.count; k += step) samples.push(v.fromBufferAttribute(pos, k).applyMatrix4(part.mesh.matrixWorld).clone());
        for (const q of samples) {
          // A little inside the part: its own faces are not in front of it.
          const d = q.lerp(part.group.position, 0.05).sub(eye);
          const len = d.length();
          if (!(len > 0)) continue;
          ray.set(eye, d.divideScalar(len));
          ray.far = len;
          for (const h of ray.intersectObjects(others, false)) xray.add(h.object.userData.part);
        }
      }
    }
    this.parts.forEach((p, i) => {
      const on = xray.has(i);
      if (on === !!p.xray) return;
      p.xray = on;
      this.applyLook(p);
    });
  }

  // The parts drawn see-through (indices).
  xrayParts() {
    if (this.xrayStale) this.updateXray();
    return this.parts.map((p, i) => (p.xray ? i : -1)).filter((i) => i >= 0);
  }

  // The canvas' pixels (RGBA) after drawing a frame.
  readPixels() {
    this.render();
    const src = this.renderer.domElement, c = document.createElement('canvas');
    c.width = src.width;
    c.height = src.height;
    const g = c.getContext('2d');
    g.drawImage(src, 0, 0);
    return g.getImageData(0, 0, c.width, c.height).data;
  }

  // Where part i shows: the pixels that change when it is hidden, those of
  // them that are red (the failing colour, lit or in shade), and the pixels
  // it covers when drawn alone (nothing else in the scene).
  visiblePixels(i) {
    const part = this.parts[i];
    if (!part || !part.group.visible) return { pixels: 0, red: 0, alone: 0 };
    const differ = (x, y, k) => Math.abs(x[k] - y[k]) + Math.abs(x[k + 1] - y[k + 1]) + Math.abs(x[k + 2] - y[k + 2]) > 30;
    const shown = this.readPixels();
    part.group.visible = false;
    const hidden = this.readPixels();
    const others = this.scene.children.filter((o) => o.visible && o !== part.group && !o.isLight);
    others.forEach((o) => { o.visible = false; });
    const empty = this.readPixels();
    part.group.visible = true;
    const alone = this.readPixels();
    others.forEach((o) => { o.visible = true; });
    this.render();
    let pixels = 0, red = 0, covers = 0;
    for (let k = 0; k < shown.length; k += 4) {
      if (differ(alone, empty, k)) ++covers;
      if (!differ(shown, hidden, k)) continue;
      ++pixels;
      if (shown[k] > 1.6 * shown[k + 1] + 20 && shown[k] > 1.6 * shown[k + 2] + 20) ++red;
    }
    return { pixels, red, alone: covers };
  }

  // --- picking and drawing -------------------------------------------------
  pick(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1,
                                  -((clientY - rect.top) / rect.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    // See-through parts let the pointer through to what they hide.
    const hits = ray.intersectObjects(this.parts.filter((p) => p.group.visible && !p.xray).map((p) => p.mesh), false);
    const partHit = hits.length ? hits[0] : null;
    // The marks drawn (contact points, pairs' centres of pressure) by their
    // distance to the ray (thousands of them: no triangles tested), the
    // nearest along the ray that is not behind the part the ray hits first.
    const reach = 1.5 * this.mark;
    let best = null, bestT = Infinity;
    for (const d of this.dotItems || []) {
      const t = d.p.clone().sub(ray.ray.origin).dot(ray.ray.direction);
      if (t < 0 || t >= bestT || ray.ray.distanceSqToPoint(d.p) > reach * reach) continue;
      best = d;
      bestT = t;
    }
    if (best && (!partHit || bestT <= partHit.distance + 2 * reach))
      return best.pair !== undefined ? { pair: best.pair } : { contact: best.contact };
    return partHit ? { part: partHit.object.userData.part } : null;
  }

  // Where the world point p is drawn: CSS pixels from the canvas' top left.
  screenOf(p) {
    const v = new THREE.Vector3(...p).project(this.camera);
    const r = this.renderer.domElement.getBoundingClientRect();
    return [((v.x + 1) / 2) * r.width, ((1 - v.y) / 2) * r.height];
  }

  requestRender() {
    if (this.needsRender) return;
    this.needsRender = true;
    requestAnimationFrame(() => this.render());
  }

  render() {
    this.needsRender = false;
    if (this.xrayStale) this.updateXray();
    this.renderer.render(this.scene, this.camera);
    this.placeLabels();
  }
}

export function pad3(v) {
  if (v === undefined || v === null) return [0, 0, 0];
  if (typeof v === 'number') return [0, 0, v];  // 2-D angular
  return [v[0] || 0, v[1] || 0, v.length > 2 ? v[2] : 0];
}
