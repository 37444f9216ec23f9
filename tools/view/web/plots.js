'use strict';
// A small time plot on a 2D canvas: several series over t, a cursor at the
// time drawn, optionally a log10 y axis (|q~| spans decades as it converges).
class TimePlot {
  constructor(canvas, title, logY) {
    this.canvas = canvas;
    this.title = title;
    this.logY = logY;
    this.t = [];
    this.series = [];  // [[y per t], ...]
    this.names = [];
    this.cursor = null;
  }
  setData(t, series, names) {
    this.t = t;
    this.series = series;
    this.names = names;
  }
  value(y) {
    if (y === null || !isFinite(y)) return null;
    return this.logY ? Math.log10(Math.max(Math.abs(y), 1e-12)) : y;
  }
  draw() {
    const c = this.canvas.getContext('2d');
    const w = this.canvas.width, h = this.canvas.height;
    const left = 48, right = 8, top = 18, bottom = 18;
    c.clearRect(0, 0, w, h);
    c.fillStyle = '#222';
    c.font = '11px sans-serif';
    c.fillText(this.title, left, 12);
    const n = this.t.length;
    if (n < 1) return;
    const t0 = this.t[0], t1 = Math.max(this.t[n - 1], t0 + 1e-9);
    // At most ~2 points per pixel column.
    const stride = Math.max(1, Math.floor(n / (2 * (w - left - right))));
    let lo = Infinity, hi = -Infinity;
    for (const s of this.series)
      for (let i = 0; i < n; i += stride) {
        const v = this.value(s[i]);
        if (v === null) continue;
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    if (!isFinite(lo)) return;
    if (hi - lo < 1e-12) { lo -= 0.5; hi += 0.5; }
    const x = (t) => left + (t - t0) / (t1 - t0) * (w - left - right);
    const y = (v) => top + (hi - v) / (hi - lo) * (h - top - bottom);
    c.strokeStyle = '#ccc';
    c.strokeRect(left, top, w - left - right, h - top - bottom);
    c.fillStyle = '#555';
    const label = (v) => this.logY ? '1e' + v.toFixed(1) : v.toPrecision(3);
    c.fillText(label(hi), 2, top + 8);
    c.fillText(label(lo), 2, h - bottom);
    c.fillText(t0.toFixed(2) + ' s', left, h - 4);
    c.fillText(t1.toFixed(2) + ' s', w - right - 48, h - 4);
    const colors = ['#4a78b8', '#d9534f', '#5cb85c', '#f0ad4e', '#8e44ad', '#16a085', '#7f8c8d'];
    this.series.forEach((s, k) => {
      c.strokeStyle = colors[k % colors.length];
      c.beginPath();
      let pen = false;
      for (let i = 0; i < n; i += stride) {
        const v = this.value(s[i]);
        if (v === null) { pen = false; continue; }
        if (pen) c.lineTo(x(this.t[i]), y(v)); else c.moveTo(x(this.t[i]), y(v));
        pen = true;
      }
      c.stroke();
      if (this.names.length > 1) {
        c.fillStyle = c.strokeStyle;
        c.fillText(this.names[k], w - right - 60, top + 12 + 11 * k);
      }
    });
    if (this.cursor !== null) {
      c.strokeStyle = '#000';
      c.beginPath();
      c.moveTo(x(this.cursor), top);
      c.lineTo(x(this.cursor), h - bottom);
      c.stroke();
    }
  }
}
