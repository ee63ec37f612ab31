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
  constructor(color, capacity, headSize) {
    this.color = color;
    this.headSize = headSize;
    const over = { color, depthTest: false, transparent: true, opacity: 0.9 };
    this.lines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial(over));
    this.lines.renderOrder = 20;
    const cone = new THREE.ConeGeometry(0.35, 1, 10).translate(0, -0.5, 0);
    this.heads = new THREE.InstancedMesh(cone, new THREE.MeshBasicMaterial(over), capacity);
    this.heads.renderOrder = 20;
    this.heads.count = 0;
    this.group = new THREE.Group();
    this.group.add(this.lines, this.heads);
  }
  set(arrows) {  // [[from Vector3, to Vector3], ...]
    const pos = new Float32Array(arrows.length * 6);
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
    arrows.forEach(([from, to], k) => {
      from.toArray(pos, 6 * k);
      to.toArray(pos, 6 * k + 3);
      d.subVectors(to, from);
      const len = d.length();
      const h = Math.min(this.headSize, 0.45 * len);
      q.setFromUnitVectors(yAxis, len > 0 ? d.divideScalar(len) : yAxis);
      m.compose(to, q, new THREE.Vector3(h, h, h));
      this.heads.setMatrixAt(k, m);
    });
    this.lines.geometry.dispose();
    this.lines.geometry = new THREE.BufferGeometry();
    this.lines.geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
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
    this.requestRender();
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
    this.requestRender();
  }

  // Translates part i by d from where setPoses put it (plan playback).
  offsetPart(i, d) {
    this.parts[i].group.position.add(d);
    this.requestRender();
  }

  setRoles(roleOf) {  // roleOf(i) -> key of kColors
    this.parts.forEach((p, i) => {
      const role = roleOf(i);
      p.role = role;
      p.material.color.set(kColors[role] || kColors.judged);
      p.material.transparent = role === 'ghost';
      p.material.opacity = role === 'ghost' ? 0.25 : 1;
    });
    this.requestRender();
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
    this.frictions = new ArrowSet(kColors.friction, 64, head);
    const dot = new THREE.SphereGeometry(1, 8, 6);
    this.dots = new THREE.InstancedMesh(dot, new THREE.MeshBasicMaterial({ color: 0x1d1f23 }), 64);
    this.dots.count = 0;
    this.motionArrows = new ArrowSet(kColors.failed, 8, head * 1.6);
    this.fixelArrows = new ArrowSet(kColors.fixel, 8, head * 1.3);
    this.motionMarks = new THREE.Group();
    this.overlay = new THREE.Group();
    this.overlay.add(this.normals.group, this.frictions.group, this.dots, this.motionArrows.group,
                     this.fixelArrows.group, this.motionMarks);
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

  drawContacts() {
    const c = this.contacts, count = c.a.length;
    const s = this.forceScale * this.arrowGain;
    // Each force is drawn as the push it is: an arrow ending at the contact
    // point, pointing into the part it acts on (a).
    const normals = [], frictions = [];
    const lift = this.dim === 2 ? 0.002 * this.size : 0;
    if (count > this.dots.instanceMatrix.count) {
      this.overlay.remove(this.dots);
      this.dots.dispose();
      this.dots = new THREE.InstancedMesh(this.dots.geometry, this.dots.material, Math.max(count, 2 * this.dots.instanceMatrix.count));
      this.overlay.add(this.dots);
    }
    const m = new THREE.Matrix4(), r = this.mark;
    for (let k = 0; k < count; ++k) {
      const p = new THREE.Vector3(c.p[3 * k], c.p[3 * k + 1], c.p[3 * k + 2] + lift);
      m.makeScale(r, r, r).setPosition(p);
      this.dots.setMatrixAt(k, m);
      const fn = c.fn[k];
      if (this.showForces && fn * s > 1e-6 * this.size) {
        const n = new THREE.Vector3(c.n[3 * k], c.n[3 * k + 1], c.n[3 * k + 2]);
        normals.push([p.clone().addScaledVector(n, -fn * s), p]);
      }
      const ft = new THREE.Vector3(c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]);
      if (this.showForces && this.showFriction && ft.length() * s > 1e-6 * this.size)
        frictions.push([p.clone().addScaledVector(ft, -s), p]);
    }
    this.dots.count = count;
    this.dots.instanceMatrix.needsUpdate = true;
    this.dots.computeBoundingSphere();
    this.normals.set(normals);
    this.frictions.set(frictions);
    this.requestRender();
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

  setFixels(fixels) {  // [{part, point, normal}]: arrows pushing into the part
    const arrows = (fixels || []).map((f) => {
      const p = new THREE.Vector3(...pad3(f.point)), n = new THREE.Vector3(...pad3(f.normal)).normalize();
      return [p.clone().addScaledVector(n, -0.08 * this.size), p];
    });
    this.fixelArrows.set(arrows);
    this.requestRender();
  }

  // --- picking and drawing -------------------------------------------------
  pick(clientX, clientY) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((clientX - rect.left) / rect.width) * 2 - 1,
                                  -((clientY - rect.top) / rect.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    const hits = ray.intersectObjects(this.parts.filter((p) => p.group.visible).map((p) => p.mesh), false);
    const partHit = hits.length ? hits[0] : null;
    // Contact points by their distance to the ray (thousands of them: no
    // triangles tested), the nearest along the ray that is not behind the
    // part the ray hits first.
    const c = this.contacts, reach = 1.5 * this.mark, p = new THREE.Vector3();
    let best = -1, bestT = Infinity;
    for (let k = 0; k < c.a.length; ++k) {
      p.set(c.p[3 * k], c.p[3 * k + 1], c.p[3 * k + 2]);
      const t = p.clone().sub(ray.ray.origin).dot(ray.ray.direction);
      if (t < 0 || t >= bestT || ray.ray.distanceSqToPoint(p) > reach * reach) continue;
      best = k;
      bestT = t;
    }
    if (best >= 0 && (!partHit || bestT <= partHit.distance + 2 * reach)) return { contact: best };
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
    this.renderer.render(this.scene, this.camera);
  }
}

export function pad3(v) {
  if (v === undefined || v === null) return [0, 0, 0];
  if (typeof v === 'number') return [0, 0, v];  // 2-D angular
  return [v[0] || 0, v[1] || 0, v.length > 2 ? v[2] : 0];
}
