// The report's signal plotter: one canvas per panel (the series of one unit) over a shared
// axis of frame indices. Drag across a panel or turn the wheel to zoom (every panel follows),
// double-click or press "Reset zoom" to see the whole capture; hovering shows the nearest
// sample. A panel with more samples in view than pixel columns draws the smallest and the
// largest of each column. Errors and failed checks are listed in #plot-errors (and counted in
// the container's data-errors), and data-drawn counts the series drawn: a browser test reads
// both back from the page.
(function () {
  'use strict';
  var root = document.getElementById('signals');
  var errorList = document.getElementById('plot-errors');
  var tip = document.getElementById('plot-tip');

  function fail(message) {
    var li = document.createElement('li');
    li.textContent = message;
    errorList.appendChild(li);
    root.dataset.errors = String(errorList.children.length);
  }
  function check(ok, message) {
    if (!ok) fail('check failed: ' + message);
    return ok;
  }
  window.addEventListener('error', function (e) {
    fail('error: ' + e.message + ' (line ' + e.lineno + ')');
  });
  root.dataset.errors = '0';

  var data = JSON.parse(document.getElementById('signal-data').textContent);
  var HEIGHT = 240;
  var MARGIN = { left: 72, right: 16, top: 12, bottom: 28 };
  var FONT = '12px system-ui, sans-serif';

  // The whole capture's extent on the shared axis.
  var full = { x0: Infinity, x1: -Infinity };
  data.series.forEach(function (s) {
    check(s.x.length === s.y.length, s.name + ': as many positions as values');
    if (s.x.length) {
      full.x0 = Math.min(full.x0, s.x[0]);
      full.x1 = Math.max(full.x1, s.x[s.x.length - 1]);
    }
  });
  var extent = { x0: full.x0, x1: full.x1 };
  // A little room on each side, so that the first and the last sample show whole.
  var room = Math.max(0.5, (full.x1 - full.x0) * 0.01);
  full.x0 -= room;
  full.x1 += room;
  var view = { x0: full.x0, x1: full.x1 };

  // Tick positions between lo and hi: steps of 1, 2 or 5 times a power of ten.
  function ticks(lo, hi, count) {
    var raw = (hi - lo) / count;
    if (!(raw > 0) || !isFinite(raw)) return [lo];
    var power = Math.pow(10, Math.floor(Math.log10(raw)));
    var step = [1, 2, 5, 10].map(function (m) { return m * power; })
      .find(function (s) { return s >= raw; });
    var out = [];
    for (var v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) {
      out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
    }
    return out;
  }
  function label(v) {
    var a = Math.abs(v);
    return a !== 0 && (a >= 1e6 || a < 1e-3) ? v.toExponential(2) : String(+v.toPrecision(6));
  }

  // The first index of sorted `xs` at or after `x`.
  function lowerBound(xs, x) {
    var lo = 0, hi = xs.length;
    while (lo < hi) {
      var mid = (lo + hi) >> 1;
      if (xs[mid] < x) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  // The samples of `s` in view, with one on each side so lines leave the plot area.
  function visible(s) {
    var i0 = Math.max(0, lowerBound(s.x, view.x0) - 1);
    var i1 = Math.min(s.x.length, lowerBound(s.x, view.x1 + 1e-9) + 1);
    return { i0: i0, i1: i1 };
  }

  function Panel(spec, index) {
    this.series = data.series.filter(function (s) { return s.panel === index; });
    var box = document.createElement('div');
    box.className = 'plot-panel';
    var legend = document.createElement('div');
    legend.className = 'plot-legend';
    this.series.forEach(function (s) {
      var item = document.createElement('span');
      item.innerHTML = '<i></i>';
      item.firstChild.style.background = s.color;
      item.appendChild(document.createTextNode(s.name + (s.unit ? ' [' + s.unit + ']' : '')));
      legend.appendChild(item);
    });
    this.canvas = document.createElement('canvas');
    this.canvas.dataset.unit = spec.unit;
    box.appendChild(legend);
    box.appendChild(this.canvas);
    document.getElementById('plot-panels').appendChild(box);
    this.unit = spec.unit;
    this.hover = null;
    this.drag = null;
    this.listen();
  }

  // The plot area in canvas pixels, and the y range of the samples in view.
  Panel.prototype.layout = function () {
    var width = this.canvas.clientWidth;
    this.area = {
      left: MARGIN.left, top: MARGIN.top,
      width: Math.max(10, width - MARGIN.left - MARGIN.right),
      height: HEIGHT - MARGIN.top - MARGIN.bottom
    };
    var lo = Infinity, hi = -Infinity;
    this.series.forEach(function (s) {
      var r = visible(s);
      for (var i = r.i0; i < r.i1; i++) {
        if (s.x[i] < view.x0 || s.x[i] > view.x1) continue;
        lo = Math.min(lo, s.y[i]);
        hi = Math.max(hi, s.y[i]);
      }
    });
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (hi === lo) { var pad = Math.abs(lo) * 0.1 || 1; lo -= pad; hi += pad; }
    var margin = (hi - lo) * 0.06;
    this.y0 = lo - margin;
    this.y1 = hi + margin;
  };
  Panel.prototype.px = function (x) {
    return this.area.left + (x - view.x0) / (view.x1 - view.x0) * this.area.width;
  };
  Panel.prototype.py = function (y) {
    return this.area.top + this.area.height - (y - this.y0) / (this.y1 - this.y0) * this.area.height;
  };

  Panel.prototype.draw = function () {
    var ratio = window.devicePixelRatio || 1;
    var c = this.canvas;
    c.style.height = HEIGHT + 'px';
    c.width = Math.round(c.clientWidth * ratio);
    c.height = Math.round(HEIGHT * ratio);
    var ctx = c.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, c.clientWidth, HEIGHT);
    this.layout();
    this.axes(ctx);
    var a = this.area;
    ctx.save();
    ctx.beginPath();
    ctx.rect(a.left, a.top, a.width, a.height);
    ctx.clip();
    var drawn = 0;
    for (var k = 0; k < this.series.length; k++) drawn += this.line(ctx, this.series[k]);
    this.overlay(ctx);
    ctx.restore();
    // Where the plot area is on the page and what it spans, for a test that reads the page.
    var box = c.getBoundingClientRect();
    c.dataset.left = String(box.left + window.scrollX + a.left);
    c.dataset.top = String(box.top + window.scrollY + a.top);
    c.dataset.width = String(a.width);
    c.dataset.height = String(a.height);
    c.dataset.x0 = String(view.x0);
    c.dataset.x1 = String(view.x1);
    c.dataset.y0 = String(this.y0);
    c.dataset.y1 = String(this.y1);
    return drawn;
  };

  Panel.prototype.axes = function (ctx) {
    var a = this.area, self = this;
    ctx.font = FONT;
    ctx.lineWidth = 1;
    ctx.strokeStyle = '#e4e4e4';
    ctx.fillStyle = '#555';
    ctx.textAlign = 'right';
    ctx.textBaseline = 'middle';
    ticks(this.y0, this.y1, 5).forEach(function (v) {
      var y = Math.round(self.py(v)) + 0.5;
      ctx.beginPath(); ctx.moveTo(a.left, y); ctx.lineTo(a.left + a.width, y); ctx.stroke();
      ctx.fillText(label(v), a.left - 6, y);
    });
    ctx.textAlign = 'center';
    ctx.textBaseline = 'top';
    ticks(view.x0, view.x1, Math.max(2, Math.floor(a.width / 90))).forEach(function (v) {
      if (v !== Math.round(v)) return;
      var x = Math.round(self.px(v)) + 0.5;
      ctx.beginPath(); ctx.moveTo(x, a.top); ctx.lineTo(x, a.top + a.height); ctx.stroke();
      ctx.fillText(label(v), x, a.top + a.height + 6);
    });
    ctx.strokeStyle = '#999';
    ctx.strokeRect(a.left + 0.5, a.top + 0.5, a.width, a.height);
    ctx.save();
    ctx.translate(14, a.top + a.height / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textBaseline = 'middle';
    ctx.fillText(this.unit || '(no unit)', 0, 0);
    ctx.restore();
    ctx.textAlign = 'right';
    ctx.textBaseline = 'bottom';
    ctx.fillText(data.axis, a.left + a.width, HEIGHT);
  };

  // One series: a line through its samples and a dot on each, or, with more samples in view
  // than pixel columns, the smallest and largest value of each column joined up. Returns 1
  // when something of it is in view.
  Panel.prototype.line = function (ctx, s) {
    var r = visible(s);
    if (r.i1 <= r.i0) return 0;
    ctx.strokeStyle = s.color;
    ctx.fillStyle = s.color;
    ctx.lineWidth = 1.5;
    ctx.lineJoin = 'round';
    ctx.beginPath();
    var n = r.i1 - r.i0;
    if (n > this.area.width) {
      var column = null, lo = 0, hi = 0;
      for (var i = r.i0; i <= r.i1; i++) {
        var x = i < r.i1 ? Math.floor(this.px(s.x[i])) : null;
        if (x !== column && column !== null) {
          ctx.lineTo(column + 0.5, this.py(lo));
          ctx.lineTo(column + 0.5, this.py(hi));
        }
        if (i === r.i1) break;
        if (x !== column) { column = x; lo = hi = s.y[i]; }
        lo = Math.min(lo, s.y[i]);
        hi = Math.max(hi, s.y[i]);
      }
      ctx.stroke();
      return 1;
    }
    for (var j = r.i0; j < r.i1; j++) {
      if (j === r.i0) ctx.moveTo(this.px(s.x[j]), this.py(s.y[j]));
      else ctx.lineTo(this.px(s.x[j]), this.py(s.y[j]));
    }
    ctx.stroke();
    if (n * 6 < this.area.width) {
      for (var k = r.i0; k < r.i1; k++) {
        ctx.beginPath();
        ctx.arc(this.px(s.x[k]), this.py(s.y[k]), 2.5, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
    return 1;
  };

  // The selection being dragged and the hovered sample.
  Panel.prototype.overlay = function (ctx) {
    var a = this.area;
    if (this.drag && this.drag.to !== null) {
      ctx.fillStyle = 'rgba(31, 119, 180, 0.12)';
      var x = Math.min(this.drag.from, this.drag.to);
      ctx.fillRect(x, a.top, Math.abs(this.drag.to - this.drag.from), a.height);
    }
    if (this.hover) {
      var h = this.hover;
      ctx.strokeStyle = h.series.color;
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(this.px(h.series.x[h.i]), this.py(h.series.y[h.i]), 5, 0, 2 * Math.PI);
      ctx.stroke();
    }
  };

  // The sample nearest to canvas point (mx, my): nearest in x within each series, then the
  // closest of those on the screen.
  Panel.prototype.nearest = function (mx, my) {
    var x = view.x0 + (mx - this.area.left) / this.area.width * (view.x1 - view.x0);
    var best = null, self = this;
    this.series.forEach(function (s) {
      var i = lowerBound(s.x, x);
      [i - 1, i].forEach(function (j) {
        if (j < 0 || j >= s.x.length) return;
        var d = Math.hypot(self.px(s.x[j]) - mx, self.py(s.y[j]) - my);
        if (!best || d < best.d) best = { series: s, i: j, d: d };
      });
    });
    return best;
  };

  Panel.prototype.listen = function () {
    var self = this, c = this.canvas;
    function at(e) {
      var r = c.getBoundingClientRect();
      return { x: e.clientX - r.left, y: e.clientY - r.top };
    }
    c.addEventListener('mousedown', function (e) {
      self.drag = { from: at(e).x, to: null };
    });
    c.addEventListener('mousemove', function (e) {
      var p = at(e);
      if (self.drag) { self.drag.to = p.x; self.draw(); return; }
      self.hover = self.nearest(p.x, p.y);
      showTip(self.hover, e);
      self.draw();
    });
    c.addEventListener('mouseleave', function () {
      self.hover = null;
      self.drag = null;
      tip.style.display = 'none';
      self.draw();
    });
    window.addEventListener('mouseup', function () {
      var d = self.drag;
      self.drag = null;
      if (d && d.to !== null && Math.abs(d.to - d.from) > 4) {
        var span = view.x1 - view.x0, a = self.area;
        var lo = view.x0 + (Math.min(d.from, d.to) - a.left) / a.width * span;
        var hi = view.x0 + (Math.max(d.from, d.to) - a.left) / a.width * span;
        zoomTo(lo, hi);
      } else if (d) {
        self.draw();
      }
    });
    c.addEventListener('wheel', function (e) {
      e.preventDefault();
      var a = self.area, span = view.x1 - view.x0;
      var x = view.x0 + (at(e).x - a.left) / a.width * span;
      var factor = e.deltaY < 0 ? 0.8 : 1.25;
      zoomTo(x - (x - view.x0) * factor, x + (view.x1 - x) * factor);
    }, { passive: false });
    c.addEventListener('dblclick', function () { zoomTo(full.x0, full.x1); });
  };

  function showTip(h, e) {
    if (!h) { tip.style.display = 'none'; return; }
    var s = h.series;
    tip.textContent = s.name + ' = ' + label(s.y[h.i]) + (s.unit ? ' ' + s.unit : '') +
      ' at ' + data.axis + ' ' + s.x[h.i];
    tip.style.left = (e.clientX + 14) + 'px';
    tip.style.top = (e.clientY + 14) + 'px';
    tip.style.display = 'block';
  }

  // Shows positions lo..hi (kept inside the capture, at least two frames wide) in every panel.
  function zoomTo(lo, hi) {
    var width = Math.max(2, Math.min(hi - lo, full.x1 - full.x0));
    lo = Math.max(full.x0, Math.min(lo, full.x1 - width));
    view.x0 = lo;
    view.x1 = lo + width;
    drawAll();
  }

  var panels = data.panels.map(function (p, i) { return new Panel(p, i); });

  function drawAll() {
    var drawn = 0;
    panels.forEach(function (p) { drawn += p.draw(); });
    document.getElementById('plot-range').textContent = data.axis + ' ' +
      Math.max(extent.x0, Math.ceil(view.x0)) + ' to ' + Math.min(extent.x1, Math.floor(view.x1)) +
      ' (of ' + extent.x0 + ' to ' + extent.x1 + ')';
    root.dataset.drawn = String(drawn);
    check(drawn === data.series.length || view.x0 !== full.x0 || view.x1 !== full.x1,
      'every series is drawn in the whole view (' + drawn + ' of ' + data.series.length + ')');
  }

  document.getElementById('plot-reset').addEventListener('click', function () {
    zoomTo(full.x0, full.x1);
  });
  window.addEventListener('resize', drawAll);
  drawAll();
})();
