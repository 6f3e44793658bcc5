// bzspline editor: moves control points and alphas, asks the server for every
// fit (POST /api/fit) and draws what comes back. No spline mathematics here.
'use strict';

(() => {
  const SVG_NS = 'http://www.w3.org/2000/svg';
  // The library's range of alpha, as the server puts it into the page.
  const [ALPHA_MIN, ALPHA_MAX] = JSON.parse(document.getElementById('alpha-range').textContent);
  const COMB_SAMPLES = 24;
  // The paper's Example 1, as the server puts it into the page.
  const EXAMPLE_1 = JSON.parse(document.getElementById('example-1').textContent);

  const $ = (id) => document.getElementById(id);
  const svg = $('canvas');
  const el = {
    grid: $('grid'), hull: $('hull'), comb: $('comb'), polygon: $('polygon'),
    curveLayer: $('curve-layer'), curve: $('curve'), knots: $('knots'),
    tangents: $('tangents'), points: $('points'), alphaLabel: $('alpha-label'),
    status: $('status'), fitJson: $('fit-json'),
  };

  // ---- state -------------------------------------------------------------
  const state = {
    points: EXAMPLE_1.map((p) => p.slice()),
    alphas: [],
    mode: 'function',
    closed: false,
    param: 'centripetal',
    through: false,
  };
  state.alphas = state.points.slice(1).map(() => 0.5);
  let fit = null; // the last successful response
  let selected = -1;
  let view = { sx: 1, tx: 0, ty: 0 }; // screen = (x * sx + tx, -y * sx + ty)
  let size = { width: 800, height: 600 }; // the canvas, measured in fitView
  const history = { undo: [], redo: [] };

  const legCount = () => (state.mode === 'curve' && state.closed ? state.points.length : state.points.length - 1);
  const snapshot = () => JSON.stringify(state);
  function restore(s) {
    Object.assign(state, JSON.parse(s));
    syncControls();
    requestFit();
  }
  function remember() {
    history.undo.push(snapshot());
    if (history.undo.length > 200) history.undo.shift();
    history.redo.length = 0;
    syncButtons();
  }
  function undo() {
    if (!history.undo.length) return;
    history.redo.push(snapshot());
    restore(history.undo.pop());
    syncButtons();
  }
  function redo() {
    if (!history.redo.length) return;
    history.undo.push(snapshot());
    restore(history.redo.pop());
    syncButtons();
  }
  function syncButtons() {
    $('undo').disabled = !history.undo.length;
    $('redo').disabled = !history.redo.length;
  }
  function fixAlphas() {
    const n = legCount();
    while (state.alphas.length < n) state.alphas.push(0.5);
    state.alphas.length = Math.max(n, 0);
  }

  // ---- status line ---------------------------------------------------------
  function say(text, isError = false) {
    el.status.textContent = text;
    el.status.classList.toggle('error', isError);
  }

  // ---- talking to the server ----------------------------------------------
  let inFlight = false;
  let dirty = false;
  let frame = 0;
  let serverRefused = false; // the status line shows the server's refusal
  function requestFit() {
    dirty = true;
    if (!frame) frame = requestAnimationFrame(flush);
  }
  async function flush() {
    frame = 0;
    if (inFlight || !dirty) return;
    dirty = false;
    inFlight = true;
    fixAlphas();
    const body = {
      points: state.points,
      mode: state.mode,
      closed: state.mode === 'curve' && state.closed,
      param: state.param,
      through: state.through,
      alphas: state.alphas,
      samples: $('show-comb').checked ? COMB_SAMPLES : 0,
    };
    const t0 = performance.now();
    try {
      const res = await fetch('/api/fit', {
        method: 'POST',
        headers: { 'Content-Type': 'application/json' },
        body: JSON.stringify(body),
      });
      const json = await res.json();
      const rt = performance.now() - t0;
      if (res.ok) {
        fit = json;
        editor.lastRoundTripMs = rt;
        $('info-build').textContent = `${json.build_ms.toFixed(3)} ms`;
        $('info-fit').textContent = `${json.fit_ms.toFixed(3)} ms`;
        $('info-rt').textContent = `${rt.toFixed(1)} ms`;
        el.fitJson.textContent = JSON.stringify(json);
        el.curve.classList.remove('stale');
        if (serverRefused && !dirty) say('Fitted.');
        serverRefused = false;
      } else {
        el.curve.classList.add('stale');
        serverRefused = true;
        say(`The server refused the fit (${res.status}): ${json.error}`, true);
      }
    } catch (e) {
      el.curve.classList.add('stale');
      serverRefused = true;
      say(`No answer from the server: ${e.message}`, true);
    } finally {
      inFlight = false;
      draw();
      editor.fits += 1;
      if (dirty) requestFit();
    }
  }

  // ---- view ----------------------------------------------------------------
  const toScreen = ([x, y]) => [x * view.sx + view.tx, -y * view.sx + view.ty];
  const toData = (sx, sy) => [(sx - view.tx) / view.sx, -(sy - view.ty) / view.sx];
  function fitView() {
    const box = svg.getBoundingClientRect();
    size = { width: box.width, height: box.height };
    const r = size;
    const xs = state.points.map((p) => p[0]);
    const ys = state.points.map((p) => p[1]);
    let [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
    if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
    const pad = 48;
    const s = Math.min((r.width - 2 * pad) / (x1 - x0), (r.height - 2 * pad) / (y1 - y0));
    view.sx = s > 0 && isFinite(s) ? s : 1;
    view.tx = r.width / 2 - ((x0 + x1) / 2) * view.sx;
    view.ty = r.height / 2 + ((y0 + y1) / 2) * view.sx;
    draw();
  }

  // ---- drawing -------------------------------------------------------------
  function node(tag, attrs, parent) {
    const n = document.createElementNS(SVG_NS, tag);
    for (const [k, v] of Object.entries(attrs)) n.setAttribute(k, v);
    if (parent) parent.appendChild(n);
    return n;
  }
  // Keeps exactly `count` children of `parent` with tag `tag`, reusing the ones
  // there (so an element under the pointer survives a redraw), and returns them.
  function pool(parent, count, tag) {
    while (parent.childElementCount > count) parent.lastElementChild.remove();
    while (parent.childElementCount < count) node(tag, {}, parent);
    return parent.children;
  }
  const fmt = (v) => (Math.abs(v) >= 1e4 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(3) : +v.toFixed(4)).toString();

  function niceStep(span, target) {
    const raw = span / target;
    const mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const f = raw / mag;
    return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * mag;
  }
  function drawGrid() {
    el.grid.replaceChildren();
    if (!$('show-grid').checked) return;
    const r = size;
    const [x0, y1] = toData(0, 0);
    const [x1, y0] = toData(r.width, r.height);
    const step = niceStep(Math.max(x1 - x0, y1 - y0), 12);
    if (!(step > 0) || !isFinite(step)) return;
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
      const [sx] = toScreen([x, 0]);
      node('line', { x1: sx, y1: 0, x2: sx, y2: r.height, class: Math.abs(x) < step / 2 ? 'axis' : '' }, el.grid);
      node('text', { x: sx + 3, y: r.height - 6 }, el.grid).textContent = fmt(x);
    }
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
      const [, sy] = toScreen([0, y]);
      node('line', { x1: 0, y1: sy, x2: r.width, y2: sy, class: Math.abs(y) < step / 2 ? 'axis' : '' }, el.grid);
      node('text', { x: 5, y: sy - 3 }, el.grid).textContent = fmt(y);
    }
  }

  function hull(points) {
    const p = points.map((q) => q.slice()).sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    if (p.length < 3) return p;
    const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const lower = [];
    for (const q of p) {
      while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], q) <= 0) lower.pop();
      lower.push(q);
    }
    const upper = [];
    for (const q of p.reverse()) {
      while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], q) <= 0) upper.pop();
      upper.push(q);
    }
    return lower.slice(0, -1).concat(upper.slice(0, -1));
  }

  // Knot points of the fit as plane points.
  function knotPoints(f) {
    if (!f || !f.knot_values) return [];
    return f.knot_values.map((v, i) => (Array.isArray(v) ? v : [f.knots[i], v]));
  }

  // The polygon whose legs the curve touches: the points, or through the
  // points the solved control polygon of the last fit.
  function legPoints() {
    if (!state.through || !fit || !fit.values) return state.points;
    return fit.values.map((v, i) => (Array.isArray(v) ? v : [fit.knots[i], v]));
  }

  function draw() {
    const pts = state.points;
    const closed = state.mode === 'curve' && state.closed;
    drawGrid();
    // hull
    if ($('show-hull').checked && pts.length >= 3) {
      el.hull.setAttribute('d', 'M' + hull(pts).map((p) => toScreen(p).join(' ')).join(' L') + ' Z');
    } else el.hull.setAttribute('d', '');
    // control polygon
    const legs = legPoints();
    el.polygon.setAttribute('d', legs.length ? 'M' + legs.map((p) => toScreen(p).join(' ')).join(' L') + (closed ? ' Z' : '') : '');
    el.polygon.classList.toggle('solved', state.through);
    // the spline: exact cubic segments in data coordinates under the view transform
    el.curveLayer.setAttribute('transform', `matrix(${view.sx} 0 0 ${-view.sx} ${view.tx} ${view.ty})`);
    el.curve.setAttribute('d', fit ? fit.svg_path : '');
    // curvature comb
    el.comb.replaceChildren();
    if (fit && fit.comb && $('show-comb').checked && fit.comb.length) {
      const r = size;
      const kmax = Math.max(...fit.comb.map((t) => Math.abs(t[4])));
      const len = kmax > 0 ? (0.08 * Math.min(r.width, r.height)) / kmax : 0;
      const tips = [];
      for (const [x, y, nx, ny, k] of fit.comb) {
        const [sx, sy] = toScreen([x, y]);
        // normal in screen coordinates (y flips); teeth point away from the centre of curvature
        const ex = sx - nx * k * len;
        const ey = sy + ny * k * len;
        node('line', { x1: sx, y1: sy, x2: ex, y2: ey }, el.comb);
        tips.push(`${ex},${ey}`);
      }
      node('polyline', { points: tips.join(' ') }, el.comb);
    }
    // knot points
    const kps = fit && $('show-knots').checked ? knotPoints(fit) : [];
    const kEls = pool(el.knots, kps.length, 'rect');
    kps.forEach((p, i) => {
      const [sx, sy] = toScreen(p);
      const r = kEls[i];
      r.setAttribute('x', sx - 4);
      r.setAttribute('y', sy - 4);
      r.setAttribute('width', 8);
      r.setAttribute('height', 8);
      r.setAttribute('transform', `rotate(45 ${sx} ${sy})`);
    });
    // tangent points on the legs
    const tps = fit && fit.tangent_points ? fit.tangent_points : [];
    const tEls = pool(el.tangents, tps.length, 'circle');
    tps.forEach((p, k) => {
      const [sx, sy] = toScreen(p);
      const c = tEls[k];
      c.setAttribute('cx', sx);
      c.setAttribute('cy', sy);
      c.setAttribute('r', 5.5);
      c.setAttribute('data-leg', k);
      c.setAttribute('data-alpha', (state.alphas[k] ?? 0.5).toFixed(4));
      c.setAttribute('class', drag && drag.kind === 'tangent' && drag.index === k ? 'tp active' : 'tp');
    });
    // control points
    const pEls = pool(el.points, pts.length, 'circle');
    pts.forEach((p, i) => {
      const [sx, sy] = toScreen(p);
      const c = pEls[i];
      c.setAttribute('cx', sx);
      c.setAttribute('cy', sy);
      c.setAttribute('r', 6.5);
      c.setAttribute('data-index', i);
      c.setAttribute('class', i === selected ? 'pt selected' : 'pt');
    });
    // side panel
    $('info-n').textContent = `${pts.length}`;
    const list = $('knot-list');
    list.replaceChildren();
    if (fit && pts.length <= 60) {
      for (const p of knotPoints(fit)) {
        const li = document.createElement('li');
        li.textContent = fit.dimension === 1 ? fmt(p[1]) : `(${fmt(p[0])}, ${fmt(p[1])})`;
        list.appendChild(li);
      }
    }
  }

  function showAlpha(k, sx, sy) {
    const a = state.alphas[k];
    const text = `α${k} = ${a.toFixed(4)}`;
    $('alpha-readout').textContent = `leg ${k}: ${a.toFixed(4)}`;
    const t = el.alphaLabel.querySelector('text');
    const rect = el.alphaLabel.querySelector('rect');
    t.textContent = text;
    t.setAttribute('x', sx + 14);
    t.setAttribute('y', sy - 12);
    const w = t.getComputedTextLength() + 12;
    rect.setAttribute('x', sx + 8);
    rect.setAttribute('y', sy - 28);
    rect.setAttribute('width', w);
    rect.setAttribute('height', 22);
    el.alphaLabel.setAttribute('visibility', 'visible');
  }

  // ---- editing -------------------------------------------------------------
  let drag = null;
  const pointer = (e) => {
    const r = svg.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };

  // Refuses a function-mode move that would break increasing x; returns the x kept.
  function checkedX(i, x) {
    if (state.mode !== 'function') return x;
    const pts = state.points;
    if (i > 0 && !(x > pts[i - 1][0])) {
      say(`x must keep increasing: point ${i} cannot go left of point ${i - 1} (x = ${fmt(pts[i - 1][0])}).`, true);
      return pts[i][0];
    }
    if (i < pts.length - 1 && !(x < pts[i + 1][0])) {
      say(`x must keep increasing: point ${i} cannot go right of point ${i + 1} (x = ${fmt(pts[i + 1][0])}).`, true);
      return pts[i][0];
    }
    return x;
  }

  // Nearest leg to a screen point: [leg, fraction along it, distance].
  function nearestLeg(sx, sy) {
    let best = [-1, 0, Infinity];
    const n = state.points.length;
    for (let k = 0; k < legCount(); k++) {
      const a = toScreen(state.points[k]);
      const b = toScreen(state.points[(k + 1) % n]);
      const dx = b[0] - a[0], dy = b[1] - a[1];
      const l2 = dx * dx + dy * dy;
      const t = l2 > 0 ? Math.min(1, Math.max(0, ((sx - a[0]) * dx + (sy - a[1]) * dy) / l2)) : 0;
      const d = Math.hypot(a[0] + t * dx - sx, a[1] + t * dy - sy);
      if (d < best[2]) best = [k, t, d];
    }
    return best;
  }

  svg.addEventListener('pointerdown', (e) => {
    if (e.button !== 0) return;
    const t = e.target;
    if (t.classList.contains('pt')) {
      remember();
      selected = +t.dataset.index;
      drag = { kind: 'point', index: selected, before: history.undo[history.undo.length - 1] };
    } else if (t.classList.contains('tp')) {
      remember();
      drag = { kind: 'tangent', index: +t.dataset.leg, before: history.undo[history.undo.length - 1] };
      const [sx, sy] = pointer(e);
      showAlpha(drag.index, sx, sy);
    } else {
      // Dragging the background pans the view.
      selected = -1;
      const [sx, sy] = pointer(e);
      drag = { kind: 'pan', from: [sx, sy], tx: view.tx, ty: view.ty };
      draw();
    }
    svg.setPointerCapture(e.pointerId);
    e.preventDefault();
  });

  svg.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const [sx, sy] = pointer(e);
    if (drag.kind === 'pan') {
      view.tx = drag.tx + sx - drag.from[0];
      view.ty = drag.ty + sy - drag.from[1];
      draw();
      return;
    }
    if (drag.kind === 'point') {
      const [x, y] = toData(sx, sy);
      const i = drag.index;
      const kept = checkedX(i, x);
      if (kept === x && el.status.classList.contains('error')) say(`Moving point ${i}.`);
      state.points[i] = [kept, y];
    } else {
      const k = drag.index;
      const legs = legPoints();
      const n = legs.length;
      const a = toScreen(legs[k]);
      const b = toScreen(legs[(k + 1) % n]);
      const dx = b[0] - a[0], dy = b[1] - a[1];
      const l2 = dx * dx + dy * dy;
      const s = l2 > 0 ? ((sx - a[0]) * dx + (sy - a[1]) * dy) / l2 : 0.5;
      // The tangent point sits at the fraction 1 - alpha of the leg.
      state.alphas[k] = Math.min(ALPHA_MAX, Math.max(ALPHA_MIN, 1 - s));
      const at = 1 - state.alphas[k];
      showAlpha(k, a[0] + at * dx, a[1] + at * dy);
    }
    draw();
    requestFit();
  });

  function endDrag() {
    if (!drag) return;
    if (drag.kind === 'pan') {
      drag = null;
      return;
    }
    if (snapshot() === drag.before) {
      history.undo.pop(); // a click without a move changes nothing
      syncButtons();
    }
    if (drag.kind === 'tangent') {
      el.alphaLabel.setAttribute('visibility', 'hidden');
      say(`Leg ${drag.index}: alpha = ${state.alphas[drag.index].toFixed(4)}.`);
    }
    drag = null;
    draw();
  }
  svg.addEventListener('pointerup', endDrag);
  // The wheel zooms about the pointer.
  svg.addEventListener('wheel', (e) => {
    e.preventDefault();
    const [px, py] = pointer(e);
    const [dx, dy] = toData(px, py);
    view.sx *= Math.exp(-e.deltaY * 0.0015);
    view.tx = px - dx * view.sx;
    view.ty = py + dy * view.sx;
    draw();
  }, { passive: false });
  svg.addEventListener('pointercancel', endDrag);

  svg.addEventListener('dblclick', (e) => {
    const [sx, sy] = pointer(e);
    const [k, t] = nearestLeg(sx, sy);
    if (k < 0) return;
    const n = state.points.length;
    const a = state.points[k];
    const b = state.points[(k + 1) % n];
    const f = Math.min(0.9, Math.max(0.1, t));
    remember();
    state.points.splice(k + 1, 0, [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]);
    state.alphas.splice(k + 1, 0, state.alphas[k] ?? 0.5);
    selected = k + 1;
    say(`Added point ${k + 1} on leg ${k}.`);
    requestFit();
    draw();
  });

  function removePoint(i) {
    const min = state.mode === 'curve' && state.closed ? 3 : 2;
    if (state.points.length <= min) {
      say(`At least ${min} points are needed.`, true);
      return;
    }
    remember();
    state.points.splice(i, 1);
    state.alphas.splice(Math.min(i, state.alphas.length - 1), 1);
    selected = -1;
    say(`Removed point ${i}.`);
    requestFit();
    draw();
  }
  svg.addEventListener('contextmenu', (e) => {
    if (e.target.classList.contains('pt')) {
      e.preventDefault();
      removePoint(+e.target.dataset.index);
    }
  });
  document.addEventListener('keydown', (e) => {
    if (['TEXTAREA', 'INPUT', 'SELECT'].includes(e.target.tagName)) return;
    const mod = e.ctrlKey || e.metaKey;
    if ((e.key === 'Delete' || e.key === 'Backspace') && selected >= 0) {
      e.preventDefault();
      removePoint(selected);
    } else if (mod && (e.key === 'z' || e.key === 'Z')) {
      e.preventDefault();
      e.shiftKey ? redo() : undo();
    } else if (mod && e.key === 'y') {
      e.preventDefault();
      redo();
    }
  });

  // ---- controls ------------------------------------------------------------
  function syncControls() {
    $('mode').value = state.mode;
    $('closed').checked = state.closed;
    $('through').checked = state.through;
    $('param').value = state.param;
    for (const n of document.querySelectorAll('.curve-only')) {
      n.classList.toggle('disabled', state.mode !== 'curve');
      n.querySelector('input, select').disabled = state.mode !== 'curve';
    }
    fixAlphas();
    draw();
  }
  $('mode').addEventListener('change', (e) => {
    const want = e.target.value;
    if (want === 'function') {
      const bad = state.points.findIndex((p, i) => i > 0 && !(p[0] > state.points[i - 1][0]));
      if (bad > 0) {
        e.target.value = state.mode;
        say(`A function y(x) needs increasing x: point ${bad} (x = ${fmt(state.points[bad][0])}) does not exceed point ${bad - 1}.`, true);
        return;
      }
    }
    remember();
    state.mode = want;
    syncControls();
    say(want === 'function' ? 'Function y(x): x must keep increasing.' : 'Parametric curve.');
    requestFit();
  });
  $('closed').addEventListener('change', (e) => {
    remember();
    state.closed = e.target.checked;
    syncControls();
    requestFit();
  });
  $('through').addEventListener('change', (e) => {
    remember();
    state.through = e.target.checked;
    say(state.through
      ? 'Through the points: drag the points the curve passes through; the solved control polygon is faint.'
      : 'Touching the legs of the control polygon.');
    requestFit();
  });
  $('param').addEventListener('change', (e) => {
    remember();
    state.param = e.target.value;
    requestFit();
  });
  for (const id of ['show-grid', 'show-hull', 'show-knots']) $(id).addEventListener('change', draw);
  $('show-comb').addEventListener('change', requestFit);
  $('undo').addEventListener('click', undo);
  $('redo').addEventListener('click', redo);
  $('fit-view').addEventListener('click', fitView);
  $('reset').addEventListener('click', () => {
    remember();
    state.param = 'centripetal';
    state.through = false;
    loadPoints(EXAMPLE_1, 'function', false);
    say("The paper's Example 1.");
  });

  // ---- import --------------------------------------------------------------
  function loadPoints(points, mode, closed) {
    state.points = points.map((p) => [p[0], p[1]]);
    state.mode = mode;
    state.closed = closed;
    state.alphas = [];
    selected = -1;
    syncControls();
    fitView();
    requestFit();
  }

  // Points from CSV/whitespace text, a JSON array of pairs, or GeoJSON.
  function parsePoints(text) {
    const trimmed = text.trim();
    if (trimmed.startsWith('{') || trimmed.startsWith('[')) {
      const j = JSON.parse(trimmed);
      if (Array.isArray(j)) return { points: j, closed: false, geo: false };
      let g = j;
      if (g.type === 'FeatureCollection') g = (g.features || [])[0];
      if (g && g.type === 'Feature') g = g.geometry;
      if (!g) throw new Error('no geometry in the GeoJSON');
      switch (g.type) {
        case 'LineString': return { points: g.coordinates, closed: false, geo: true };
        case 'MultiLineString': return { points: g.coordinates[0], closed: false, geo: true };
        case 'Polygon': {
          const ring = g.coordinates[0].slice();
          const [a, b] = [ring[0], ring[ring.length - 1]];
          if (ring.length > 1 && a[0] === b[0] && a[1] === b[1]) ring.pop();
          return { points: ring, closed: true, geo: true };
        }
        default: throw new Error(`GeoJSON ${g.type} is not a LineString or Polygon`);
      }
    }
    const points = [];
    trimmed.split(/\r?\n/).forEach((line, n) => {
      const cells = line.split(/[,;\t ]+/).filter((c) => c !== '');
      if (!cells.length || line.trim().startsWith('#')) return;
      const nums = cells.slice(0, 2).map(Number);
      if (nums.length < 2 || nums.some((v) => !isFinite(v))) {
        if (points.length === 0 && n === 0) return; // a header line
        throw new Error(`line ${n + 1}: expected two numbers, found "${line.trim()}"`);
      }
      points.push(nums);
    });
    return { points, closed: false, geo: false };
  }

  function importText(text, source) {
    try {
      const { points, closed, geo } = parsePoints(text);
      if (points.length < 2) throw new Error('fewer than 2 points');
      const bad = points.findIndex((p) => !Array.isArray(p) || p.length < 2 || !isFinite(p[0]) || !isFinite(p[1]));
      if (bad >= 0) throw new Error(`point ${bad} is not a pair of numbers`);
      const increasing = points.every((p, i) => i === 0 || p[0] > points[i - 1][0]);
      const mode = !geo && !closed && increasing ? 'function' : 'curve';
      remember();
      loadPoints(points, mode, closed);
      say(`Loaded ${points.length} points from ${source} as a ${mode === 'function' ? 'function y(x)' : closed ? 'closed curve' : 'curve'}.`);
    } catch (e) {
      say(`Could not read ${source}: ${e.message}`, true);
    }
  }
  $('file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (f) importText(await f.text(), f.name);
    e.target.value = '';
  });
  $('paste').addEventListener('click', () => $('paste-dialog').showModal());
  $('paste-dialog').addEventListener('close', () => {
    if ($('paste-dialog').returnValue === 'ok') importText($('paste-text').value, 'the pasted text');
  });

  // ---- export --------------------------------------------------------------
  function download(name, type, text) {
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([text], { type }));
    a.download = name;
    document.body.appendChild(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }
  $('export-json').addEventListener('click', () => {
    if (!fit) return say('Nothing fitted yet.', true);
    const { fit_ms, build_ms, ...rest } = fit;
    download('bzspline-fit.json', 'application/json', JSON.stringify(rest, null, 2) + '\n');
  });
  $('export-csv').addEventListener('click', () => {
    download('bzspline-points.csv', 'text/csv', 'x,y\n' + state.points.map((p) => `${p[0]},${p[1]}`).join('\n') + '\n');
  });
  $('export-svg').addEventListener('click', () => {
    if (!fit) return say('Nothing fitted yet.', true);
    const xs = state.points.map((p) => p[0]);
    const ys = state.points.map((p) => p[1]);
    const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
    const m = 0.05 * Math.max(x1 - x0, y1 - y0, 1e-9);
    const closed = state.mode === 'curve' && state.closed;
    const poly = state.points.map((p) => p.join(',')).join(' ');
    const svgText = `<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" viewBox="${x0 - m} ${-(y1 + m)} ${x1 - x0 + 2 * m} ${y1 - y0 + 2 * m}" width="800">
  <g transform="scale(1 -1)" fill="none" vector-effect="non-scaling-stroke">
    <${closed ? 'polygon' : 'polyline'} points="${poly}" stroke="#7d8696" stroke-dasharray="6 5" stroke-width="1" vector-effect="non-scaling-stroke"/>
    <path d="${fit.svg_path}" stroke="#1f5fbf" stroke-width="2.5" vector-effect="non-scaling-stroke"/>
  </g>
</svg>
`;
    download('bzspline-curve.svg', 'image/svg+xml', svgText);
  });

  // ---- start ---------------------------------------------------------------
  const editor = {
    state,
    fits: 0,
    lastRoundTripMs: NaN,
    get fit() { return fit; },
    loadPoints,
    importText,
    idle: () => !inFlight && !dirty && !frame,
  };
  window.bzEditor = editor;
  window.addEventListener('resize', fitView);
  syncButtons();
  syncControls();
  fitView();
  requestFit();
})();
