// Force versus time of one contact pair over a simulation (the paper's
// Figs. 7 and 13): the sum of the normal forces of the pair's contact points
// at each tick, and the sum of their friction forces' magnitudes. A marker
// follows the scrubber; the failure is a red line.

import { kColors } from './style.js';

export class ForceChart {
  constructor(canvas, frames, names, unit, failureFrame) {
    this.canvas = canvas;
    this.frames = frames;
    this.names = names;
    this.unit = unit;
    this.failureFrame = failureFrame;
    this.frame = 0;
    this.markerX = null;
    this.pair = [-1, -1];
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  select(a, b) {
    this.pair = [a, b];
    if (this.onSelect) this.onSelect(a, b);
    const same = (x, y) => (x === a && y === b) || (x === b && y === a);
    this.normal = [];
    this.friction = [];
    for (const f of this.frames) {
      const c = f.contacts;
      let n = 0, t = 0;
      for (let k = 0; k < c.a.length; ++k) {
        if (!same(c.a[k], c.b[k])) continue;
        n += c.fn[k];
        t += Math.hypot(c.ft[3 * k], c.ft[3 * k + 1], c.ft[3 * k + 2]);
      }
      this.normal.push(n);
      this.friction.push(t);
    }
    this.draw();
  }

  setFrame(k) {
    this.frame = k;
    this.draw();
  }

  draw() {
    const cv = this.canvas, dpr = window.devicePixelRatio || 1;
    const w = cv.clientWidth || 600, h = cv.clientHeight || 150;
    cv.width = Math.round(w * dpr);
    cv.height = Math.round(h * dpr);
    const g = cv.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const frames = this.frames;
    if (!frames.length || !this.normal) return;
    const L = 56, R = 10, T = 18, B = 22;
    const t0 = frames[0].time, t1 = Math.max(frames[frames.length - 1].time, t0 + 1e-12);
    const fmax = Math.max(1e-12, ...this.normal, ...this.friction) * 1.08;
    const x = (t) => L + ((t - t0) / (t1 - t0)) * (w - L - R);
    const y = (f) => h - B - (f / fmax) * (h - T - B);
    // Axes and labels.
    g.strokeStyle = '#bbb';
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(L, T); g.lineTo(L, h - B); g.lineTo(w - R, h - B);
    g.stroke();
    g.fillStyle = '#555';
    g.font = '11px system-ui, sans-serif';
    g.textAlign = 'right';
    g.fillText(fmax.toPrecision(3), L - 4, T + 4);
    g.fillText('0', L - 4, h - B);
    g.textAlign = 'left';
    g.fillText('time (s) ' + t0.toPrecision(3) + ' … ' + t1.toPrecision(3), L, h - 6);
    const [a, b] = this.pair;
    const name = (i) => (i >= 0 ? this.names[i] : 'world');
    g.fillText(a === -1 && b === -1 ? 'click a contact to plot its pair' :
               'force between ' + name(a) + ' and ' + name(b) + ' (' + this.unit + '): normal, friction', L + 4, 12);
    // The failure.
    if (this.failureFrame >= 0) {
      g.strokeStyle = kColors.failed;
      g.beginPath();
      const fx = x(frames[this.failureFrame].time);
      g.moveTo(fx, T); g.lineTo(fx, h - B);
      g.stroke();
    }
    // The two curves.
    const curve = (vals, color) => {
      g.strokeStyle = color;
      g.lineWidth = 1.8;
      g.beginPath();
      vals.forEach((v, k) => (k ? g.lineTo(x(frames[k].time), y(v)) : g.moveTo(x(frames[k].time), y(v))));
      g.stroke();
    };
    curve(this.normal, kColors.normal);
    curve(this.friction, kColors.friction);
    // The scrubber's marker.
    const k = Math.min(this.frame, frames.length - 1);
    this.markerX = x(frames[k].time);
    g.strokeStyle = '#111';
    g.lineWidth = 1;
    g.setLineDash([4, 3]);
    g.beginPath();
    g.moveTo(this.markerX, T); g.lineTo(this.markerX, h - B);
    g.stroke();
    g.setLineDash([]);
    g.fillStyle = kColors.normal;
    g.beginPath();
    g.arc(this.markerX, y(this.normal[k]), 3.5, 0, 2 * Math.PI);
    g.fill();
  }
}
