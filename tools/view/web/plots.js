'use strict';
// A small time plot on a 2D canvas: several series over t, a cursor at the
// time drawn, optionally a log10 y axis (|q~| spans decades as it converges).
//
// Every peak is drawn however many samples share a pixel: each pixel column
// holds the min and max of the samples in it (and, for a log the server sent
// every k-th frame of, of the frames between them: the envelope), and the
// line runs through both. Axis ticks fall on round numbers: 1, 2 or 5 times a
// power of ten on a linear axis, whole decades on a log axis.

const PLOT_COLORS = ['#4a78b8', '#d9534f', '#5cb85c', '#f0ad4e', '#8e44ad', '#16a085', '#7f8c8d'];
const SUPERSCRIPT = {'-': '⁻', '0': '⁰', '1': '¹', '2': '²', '3': '³', '4': '⁴', '5': '⁵', '6': '⁶', '7': '⁷',
                     '8': '⁸', '9': '⁹'};

// Round ticks in [lo, hi]: steps of 1, 2 or 5 times a power of ten, about `count` of them.
function linearTicks(lo, hi, count) {
  if (!(hi > lo) || !isFinite(lo) || !isFinite(hi)) return isFinite(lo) ? [lo] : [];
  const raw = (hi - lo) / Math.max(count, 1);
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * power).find((s) => s >= raw) || 10 * power;
  const ticks = [];
  // At most 50: a span below the values' own resolution must not loop forever.
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9 && ticks.length < 50; v += step)
    ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return ticks;
}

// A tick's text without floating-point noise (0.30000000000000004 reads 0.3),
// short enough for the margin: 5e4 rather than 50000.
function tickText(v) {
  const a = Math.abs(v);
  if (a >= 1e4 || (a > 0 && a < 1e-3)) return Number(v.toPrecision(3)).toExponential().replace('e+', 'e');
  return String(Number(v.toPrecision(6)));
}

function decadeText(d) {
  return '10' + String(d).split('').map((ch) => SUPERSCRIPT[ch]).join('');
}

class TimePlot {
  constructor(canvas, title, logY) {
    this.canvas = canvas;
    this.title = title;
    this.logY = logY;
    this.t = [];
    this.series = [];    // [[y per t], ...]
    this.envelope = null;  // {lo: [[y per t], ...], hi: [...]}: the range each sample stands for
    this.names = [];
    this.cursor = null;
    this.cache = null;   // the pixel columns of the data drawn last
  }
  setData(t, series, names, envelope) {
    this.t = t;
    this.series = series;
    this.names = names;
    this.envelope = envelope || null;
    this.cache = null;
  }
  value(y) {
    if (y === null || y === undefined || !isFinite(y)) return null;
    if (!this.logY) return y;
    return y === 0 ? null : Math.log10(Math.abs(y));  // a log axis has no zero
  }
  // Per series, per pixel column of `width`: {lo, hi, first, last} of the
  // values in it (null where none), and the overall range.
  columns(width) {
    if (this.cache && this.cache.width === width) return this.cache;
    const n = this.t.length;
    const t0 = this.t[0], t1 = Math.max(this.t[n - 1], t0 + Math.max(1e-9, Math.abs(t0) * 1e-9));
    let lo = Infinity, hi = -Infinity;
    const all = this.series.map((s, k) => {
      const cols = new Array(width).fill(null);
      const envLo = this.envelope ? this.envelope.lo[k] : null, envHi = this.envelope ? this.envelope.hi[k] : null;
      for (let i = 0; i < n; i++) {
        const v = this.value(s[i]);
        if (v === null) continue;
        let a = v, b = v;
        if (envLo) {
          const l = this.value(envLo[i]), h = this.value(envHi[i]);
          // On a log axis the envelope's ends are magnitudes: take both orders.
          for (const e of [l, h]) if (e !== null) { a = Math.min(a, e); b = Math.max(b, e); }
        }
        const x = Math.min(width - 1, Math.floor((this.t[i] - t0) / (t1 - t0) * width));
        const c = cols[x];
        if (c === null) cols[x] = {lo: a, hi: b, first: v, last: v};
        else { c.lo = Math.min(c.lo, a); c.hi = Math.max(c.hi, b); c.last = v; }
        lo = Math.min(lo, a);
        hi = Math.max(hi, b);
      }
      return cols;
    });
    this.cache = {width, t0, t1, lo, hi, all};
    return this.cache;
  }
  // The range of the values drawn [lo, hi], in the data's units (tests read it).
  extent() {
    const w = this.canvas.width - TimePlot.LEFT - TimePlot.RIGHT;
    if (this.t.length === 0) return null;
    const c = this.columns(w);
    if (!isFinite(c.lo)) return null;
    return this.logY ? [Math.pow(10, c.lo), Math.pow(10, c.hi)] : [c.lo, c.hi];
  }
  draw() {
    const c = this.canvas.getContext('2d');
    const w = this.canvas.width, h = this.canvas.height;
    const left = TimePlot.LEFT, right = TimePlot.RIGHT, top = 20, bottom = 18;
    c.clearRect(0, 0, w, h);
    c.fillStyle = '#222';
    c.font = '11px sans-serif';
    c.textAlign = 'left';
    c.fillText(this.title, 2, 12);
    const n = this.t.length;
    if (n < 1) return;
    const pw = w - left - right, ph = h - top - bottom;
    const data = this.columns(pw);
    let lo = data.lo, hi = data.hi;
    if (!isFinite(lo)) return;
    let ticks;
    if (this.logY) {
      lo = Math.floor(lo);
      hi = Math.max(Math.ceil(hi), lo + 1);
      const every = Math.ceil((hi - lo) / 5);
      ticks = [];
      for (let d = hi; d >= lo; d -= every) ticks.push(d);
    } else {
      if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) { lo -= 0.5; hi += 0.5; }
      const pad = 0.04 * (hi - lo);
      lo -= pad;
      hi += pad;
      ticks = linearTicks(lo, hi, 4);
    }
    const x = (t) => left + (t - data.t0) / (data.t1 - data.t0) * pw;
    const y = (v) => top + (hi - v) / (hi - lo) * ph;
    // Grid and labels.
    c.strokeStyle = '#eee';
    c.fillStyle = '#555';
    c.textAlign = 'right';
    for (const v of ticks) {
      c.beginPath();
      c.moveTo(left, y(v));
      c.lineTo(w - right, y(v));
      c.stroke();
      c.fillText(this.logY ? decadeText(v) : tickText(v), left - 4, y(v) + 4);
    }
    c.textAlign = 'center';
    for (const t of linearTicks(data.t0, data.t1, 5)) {
      c.beginPath();
      c.moveTo(x(t), top);
      c.lineTo(x(t), h - bottom);
      c.stroke();
      c.fillText(tickText(t) + (t === 0 ? ' s' : ''), x(t), h - 4);
    }
    c.strokeStyle = '#ccc';
    c.strokeRect(left, top, pw, ph);
    // The series: through each column's first, min, max and last value.
    data.all.forEach((cols, k) => {
      c.strokeStyle = PLOT_COLORS[k % PLOT_COLORS.length];
      c.beginPath();
      let pen = false;
      cols.forEach((col, px) => {
        if (col === null) { pen = false; return; }
        const cx = left + px + 0.5;
        if (pen) c.lineTo(cx, y(col.first)); else c.moveTo(cx, y(col.first));
        c.lineTo(cx, y(col.lo));
        c.lineTo(cx, y(col.hi));
        c.lineTo(cx, y(col.last));
        pen = true;
      });
      c.stroke();
    });
    // A legend only when there is more than one series, on the title's line.
    if (this.names.length > 1) {
      c.textAlign = 'right';
      let at = w - right;
      for (let k = this.names.length - 1; k >= 0; k--) {
        c.fillStyle = PLOT_COLORS[k % PLOT_COLORS.length];
        c.fillText(this.names[k], at, 12);
        at -= c.measureText(this.names[k]).width + 6;
      }
    }
    if (this.cursor !== null) {
      c.strokeStyle = '#000';
      c.beginPath();
      c.moveTo(x(this.cursor), top);
      c.lineTo(x(this.cursor), h - bottom);
      c.stroke();
    }
  }
}
TimePlot.LEFT = 44;
TimePlot.RIGHT = 8;
