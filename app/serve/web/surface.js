// hotmesh serve: the page's surfaces, section 4.2 on CAD faces of any shape (issue 23). With
// "Surface (t, s)" ticked, Reconstruct posts to /api/surfaces and this shows the answer:
//   - a residual map per face: the face's (t, s) rectangle (drawn with the face's own
//     proportions) and each FEM node at its (t_j, s_j), coloured by |d(t_j, s_j) - δ_j| on a
//     log scale shared by all faces; hovering a node tells its id, line, face, t, s, distance
//     to the face and residual;
//   - a 3D view on a canvas, orthographic: the CAD faces' sample grid S(t, s) in grey, the
//     deformed faces S + A d(t, s) shaded by |d|, the FEM nodes at Q + A δ; A is the page's
//     amplification slider; drag rotates, the wheel zooms.
// Plain JavaScript, no library (the page works offline); app.js holds the workflow.
'use strict';

const view3d = { yaw: 0, pitch: 0, zoom: 1, center: [0, 0, 0], size: 1 };

/// Surface (t, s) is ticked unless the ticked faces are one surface of revolution: the service
/// chooses as hotmesh deform and check do (POST /api/models/{id}/mode: meridional only when every
/// face turns about one axis, the typed one or else one they share) and the note says why.
/// Ticking faces or typing an axis asks again; the user may change the box afterwards. An
/// answer a later question has overtaken is dropped; Reconstruct waits for the last one.
let modeQuestions = 0;

function updateSurfaceMode() {
  if (!state.model) return;
  state.modeChosen = chooseSurfaceMode(++modeQuestions);
}

/// Asks the service for the ticked faces' mode and ticks the box by its answer, unless a later
/// question came since. Never throws: a failed question leaves the box and says so.
async function chooseSurfaceMode(question) {
  const faces = selectedFaces();
  const note = $('mode-note');
  let text = '';
  if (faces.length === 0) {
    setSurfaceMode(false);
  } else {
    const request = { faces };
    if ($('axis').dataset.typed === 'true') {
      try {
        request.axis = axisRequest();
      } catch {
        // a malformed axis is Reconstruct's error to show; meanwhile the faces' own applies
      }
    }
    try {
      const chosen = await api('POST', `/api/models/${state.model.model}/mode`, request);
      if (question !== modeQuestions) return;
      setSurfaceMode(chosen.mode === 'surface');
      text = chosen.mode === 'surface' ? `surfaces: ${chosen.reason}` : 'one surface of revolution: its meridional curve';
    } catch (error) {
      if (question !== modeQuestions) return;
      text = `mode not chosen: ${error.message}`;
    }
  }
  note.textContent = text;
  note.dataset.faces = faces.join(',');
}

function setSurfaceMode(on) {
  $('surface-mode').checked = on;
  $('form').disabled = on;
}

async function reconstructSurface(request) {
  if (!state.model || $('no-cad').checked) throw new Error('a surface is reconstructed on CAD faces: load a CAD file and tick its faces');
  request.model = state.model.model;
  request.faces = selectedFaces();
  if (request.faces.length === 0) throw new Error('tick the faces the FEM nodes lie on');
  request.grid = 24;
  setSurface(await api('POST', '/api/surfaces', request));
}

function setSurface(surface) {
  hideTooltip();
  hideSurfaceTooltip();
  state.surface = surface;
  state.curve = null;
  $('curve-box').hidden = true;
  $('surface-box').hidden = false;
  $('downloads-what').textContent = 'Deformed faces:';
  const automatic = surfaceAmplification(surface);
  const slider = $('amplification');
  slider.disabled = false;
  slider.value = String(Math.log10(automatic));
  setAmplification(automatic);
  showSummary(surface);
  showDownloads(surface);
  resetView3d();
  drawResidualMaps(surface);
}

// ---- sizes and colours -------------------------------------------------------------------

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const length3 = (a) => Math.hypot(a[0], a[1], a[2]);

/// The corners of the box around the faces' grids.
function surfaceBounds(surface) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const face of surface.faces) {
    for (const p of face.grid.points) {
      for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); }
    }
  }
  return { lo, hi };
}

/// As the curves' (curve_outputs.cpp): the largest deflection drawn a tenth of the faces' size,
/// rounded down to 1, 2 or 5 times a power of ten, at least 1.
function surfaceAmplification(surface) {
  const { lo, hi } = surfaceBounds(surface);
  const size = length3(sub(hi, lo));
  let largest = 0;
  for (const node of [...surface.nodes, ...surface.left_out]) largest = Math.max(largest, length3(node.deflection));
  for (const face of surface.faces) for (const d of face.grid.deflections) largest = Math.max(largest, length3(d));
  if (!(largest > 0) || !(size > 0)) return 1;
  const x = (0.1 * size) / largest;
  const decade = Math.pow(10, Math.floor(Math.log10(x)));
  const nice = [5, 2, 1].map((m) => m * decade).find((v) => v <= x * (1 + 1e-12)) || decade;
  return Math.max(1, nice);
}

/// A colour of a scale of stops at fraction f in [0, 1], as rgb().
function colourAt(stops, f, light = 1) {
  const x = Math.min(Math.max(Number.isFinite(f) ? f : 0, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2);
  const c = stops[i].map((v, k) => (v + (stops[i + 1][k] - v) * (x - i)) * light);
  return `rgb(${c.map((v) => Math.round(v)).join(',')})`;
}
const kResidualStops = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];  // viridis
const kDeflectionStops = [[70, 100, 190], [150, 190, 225], [235, 225, 200], [235, 140, 80], [180, 30, 40]];

/// The log10 range of the residuals, whole decades around the data (as the curves' bar chart).
function residualScale(nodes) {
  const positive = nodes.map((n) => n.residual).filter((r) => r > 0);
  const lo = positive.length ? Math.floor(Math.max(Math.log10(Math.min(...positive)), -20)) : -16;
  const hi = Math.max(positive.length ? Math.ceil(Math.log10(Math.max(...positive))) : -15, lo + 1);
  const at = (r) => (r > 0 ? (Math.log10(r) - lo) / (hi - lo) : 0);
  return { lo, hi, at, exact: positive.length === 0 };
}

// ---- residual maps over (t, s) -------------------------------------------------------------

/// Length of the face along t (at mid s) over its length along s (at mid t), from its grid.
function faceAspect(face) {
  const n = face.grid.size, p = face.grid.points;
  const mid = Math.floor(n / 2);
  let along = 0, across = 0;
  for (let i = 0; i + 1 < n; i++) {
    along += length3(sub(p[(i + 1) * n + mid], p[i * n + mid]));
    across += length3(sub(p[mid * n + i + 1], p[mid * n + i]));
  }
  return along > 0 && across > 0 ? along / across : 1;
}

function drawResidualMaps(surface) {
  const box = $('residual-maps');
  box.replaceChildren();
  const scale = residualScale(surface.nodes);
  drawResidualLegend(scale, surface.unit);
  const summaries = new Map(surface.summary.faces.map((f) => [f.id, f]));
  for (const face of surface.faces) {
    const aspect = faceAspect(face);
    const w = Math.round(Math.max(120, Math.min(480, 360 * aspect)));
    const h = Math.round(Math.max(120, Math.min(360, 480 / aspect)));
    const left = 46, top = 44, right = 14, bottom = 40;
    const svg = element('svg', {
      viewBox: `0 0 ${w + left + right} ${h + top + bottom}`, width: w + left + right, height: h + top + bottom,
      class: 'residual-map', id: `residual-map-${face.id}`, 'data-face': face.id,
    }, box);
    const [t0, t1] = face.parameter_range.t, [s0, s1] = face.parameter_range.s;
    const x = (t) => left + ((t - t0) / (t1 - t0 || 1)) * w;
    const y = (s) => top + h - ((s - s0) / (s1 - s0 || 1)) * h;
    element('rect', { x: left, y: top, width: w, height: h, class: 'map-frame' }, svg);
    for (const t of face.knots.t) element('line', { x1: x(t), x2: x(t), y1: top, y2: top + h, class: 'map-knot' }, svg);
    for (const s of face.knots.s) element('line', { x1: left, x2: left + w, y1: y(s), y2: y(s), class: 'map-knot' }, svg);
    const fit = summaries.get(face.id) || {};
    const text = (tx, ty, content, attributes = {}) => {
      element('text', { x: tx, y: ty, class: 'map-label', ...attributes }, svg).textContent = content;
    };
    text(left, 16, `face ${face.id} (${face.kind}): max residual ${formatNumber(fit.max_residual)}`, { class: 'map-title' });
    text(left, 34, `${fit.nodes} nodes, ${fit.method}, ${fit.poles ? fit.poles.join(' × ') : '?'} poles`);
    text(left, top + h + 16, formatNumber(t0));
    text(left + w, top + h + 16, formatNumber(t1), { 'text-anchor': 'end' });
    text(left + w / 2, top + h + 32, 't →', { 'text-anchor': 'middle' });
    text(left - 6, top + h, formatNumber(s0), { 'text-anchor': 'end' });
    text(left - 6, top + 10, formatNumber(s1), { 'text-anchor': 'end' });
    text(left - 6, top + h / 2, 's ↑', { 'text-anchor': 'end' });
    // Least residual first, so the worst are drawn on top; the worst ringed.
    const nodes = surface.nodes.map((node, k) => ({ node, k })).filter(({ node }) => node.face === face.id)
      .sort((a, b) => a.node.residual - b.node.residual);
    nodes.forEach(({ node, k }, i) => {
      const worst = i === nodes.length - 1;
      const dot = element('circle', {
        cx: x(node.t), cy: y(node.s), r: worst ? 6 : 4.5, fill: colourAt(kResidualStops, scale.at(node.residual)),
        class: worst ? 'map-node worst' : 'map-node', 'data-k': k,
      }, svg);
      dot.addEventListener('pointerenter', (event) => showSurfaceTooltip(node, event));
      dot.addEventListener('pointerleave', hideSurfaceTooltip);
    });
  }
}

function drawResidualLegend(scale, unit) {
  const box = $('residual-legend');
  box.replaceChildren();
  const svg = element('svg', { viewBox: '0 0 760 38', width: 760, height: 38, id: 'residual-legend-bar' }, box);
  const steps = 40, left = 20, width = 300;
  for (let i = 0; i < steps; i++) {
    element('rect', {
      x: left + (i * width) / steps, y: 4, width: width / steps + 0.5, height: 12,
      fill: colourAt(kResidualStops, (i + 0.5) / steps),
    }, svg);
  }
  for (let e = scale.lo; e <= scale.hi; e += Math.max(1, Math.round((scale.hi - scale.lo) / 5))) {
    const lx = left + ((e - scale.lo) / (scale.hi - scale.lo)) * width;
    element('text', { x: lx, y: 30, 'text-anchor': 'middle', class: 'map-label' }, svg).textContent = `1e${e}`;
  }
  const note = scale.exact ? 'every residual is 0' : 'log scale; the worst node of each face ringed';
  element('text', { x: left + width + 14, y: 14, class: 'map-label' }, svg).textContent = `residual [${unit}], ${note}`;
}

function showSurfaceTooltip(node, event) {
  const tip = $('surface-tooltip');
  const lines = [
    ['node', node.label],
    ['line', formatNumber(node.line)],
    ['face', formatNumber(node.face)],
    ['t', formatNumber(node.t)],
    ['s', formatNumber(node.s)],
    ['distance to CAD', formatNumber(node.distance)],
    ['residual', formatNumber(node.residual)],
  ];
  placeTooltip(tip, lines, $('surface-box'), node, event);
}

function hideSurfaceTooltip() { $('surface-tooltip').hidden = true; }

// ---- the 3D view ---------------------------------------------------------------------------

function resetView3d() {
  const { lo, hi } = surfaceBounds(state.surface);
  view3d.center = lo.map((v, k) => (v + hi[k]) / 2);
  view3d.size = Math.max(length3(sub(hi, lo)), 1e-12);
  view3d.yaw = -0.6;   // about z, so that x runs to the right and away
  view3d.pitch = 0.55; // looking down on the x-y plane
  view3d.zoom = 1;
  // Zoomed so that the faces, as first seen, fill most of the canvas.
  const canvas = $('view3d');
  const width = canvas.clientWidth, height = canvas.clientHeight;
  if (width > 0) {
    const project = projector(width, height);
    let [dx, dy] = [0, 0];
    for (const face of state.surface.faces) {
      for (const p of face.grid.points) {
        const [px, py] = project(p);
        dx = Math.max(dx, Math.abs(px - width / 2));
        dy = Math.max(dy, Math.abs(py - height / 2));
      }
    }
    if (dx > 0 && dy > 0) view3d.zoom = Math.min((0.42 * width) / dx, (0.38 * height) / dy);
  }
  drawSurface3d();
}

/// Orthographic projection: turn about z by yaw, tilt by pitch; z is up on the screen.
/// Returns [screen x, screen y, depth] in pixels (depth grows away from the viewer).
function projector(width, height) {
  const cy = Math.cos(view3d.yaw), sy = Math.sin(view3d.yaw);
  const cp = Math.cos(view3d.pitch), sp = Math.sin(view3d.pitch);
  const scale = (view3d.zoom * 0.85 * Math.min(width, height)) / view3d.size;
  return (p) => {
    const [x, y, z] = sub(p, view3d.center);
    const x1 = cy * x - sy * y, y1 = sy * x + cy * y;
    return [width / 2 + scale * x1, height / 2 - scale * (cp * z + sp * y1), scale * (cp * y1 - sp * z)];
  };
}

function drawSurface3d() {
  const surface = state.surface;
  const canvas = $('view3d');
  if (!surface || canvas.clientWidth === 0) return;
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth, height = canvas.clientHeight;
  canvas.width = Math.round(width * ratio);
  canvas.height = Math.round(height * ratio);
  const g = canvas.getContext('2d');
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, width, height);
  const project = projector(width, height);
  const a = state.amplification;
  const moved = (p, d) => [p[0] + a * d[0], p[1] + a * d[1], p[2] + a * d[2]];

  // The CAD faces: their grid lines in grey, behind.
  g.strokeStyle = '#a9adb3';
  g.lineWidth = 0.8;
  for (const face of surface.faces) {
    const n = face.grid.size;
    const at = (i, j) => project(face.grid.points[i * n + j]);
    g.beginPath();
    for (let i = 0; i < n; i++) {
      for (let j = 0; j < n; j++) {
        const [px, py] = at(i, j);
        if (j === 0) g.moveTo(px, py); else g.lineTo(px, py);
      }
    }
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const [px, py] = at(i, j);
        if (i === 0) g.moveTo(px, py); else g.lineTo(px, py);
      }
    }
    g.stroke();
  }

  // The deformed faces: grid cells far to near, shaded by |d| and lit from the viewer.
  let largest = 0;
  for (const face of surface.faces) for (const d of face.grid.deflections) largest = Math.max(largest, length3(d));
  const cells = [];
  for (const face of surface.faces) {
    const n = face.grid.size;
    const q = face.grid.points.map((p, k) => project(moved(p, face.grid.deflections[k])));
    const size = face.grid.deflections.map(length3);
    for (let i = 0; i + 1 < n; i++) {
      for (let j = 0; j + 1 < n; j++) {
        const k = [i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1];
        const corners = k.map((m) => q[m]);
        const u = sub(corners[2], corners[0]), v = sub(corners[3], corners[1]);
        const normal = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        const facing = Math.abs(normal[2]) / (length3(normal) || 1);
        const depth = corners.reduce((sum, c) => sum + c[2], 0) / 4;
        const magnitude = k.reduce((sum, m) => sum + size[m], 0) / 4;
        cells.push({ corners, depth, fill: colourAt(kDeflectionStops, largest > 0 ? magnitude / largest : 0, 0.55 + 0.45 * facing) });
      }
    }
  }
  cells.sort((p, r) => r.depth - p.depth);
  g.lineWidth = 0.5;
  g.strokeStyle = 'rgba(40, 40, 40, 0.45)';
  for (const cell of cells) {
    g.beginPath();
    cell.corners.forEach(([px, py], m) => (m ? g.lineTo(px, py) : g.moveTo(px, py)));
    g.closePath();
    g.fillStyle = cell.fill;
    g.fill();
    g.stroke();
  }

  // The FEM nodes, on top: used ones at Q + A δ, those left out hollow at Q.
  g.fillStyle = '#1f5bbf';
  for (const node of surface.nodes) {
    const [px, py] = project(moved(node.point, node.deflection));
    g.beginPath();
    g.arc(px, py, 2.2, 0, 2 * Math.PI);
    g.fill();
  }
  g.strokeStyle = '#000';
  g.lineWidth = 1.2;
  for (const node of surface.left_out) {
    const [px, py] = project(node.point);
    g.beginPath();
    g.arc(px, py, 3.5, 0, 2 * Math.PI);
    g.stroke();
  }
  g.fillStyle = '#445';
  g.font = '12px system-ui, sans-serif';
  g.fillText(`deflection ×${formatNumber(Number(a.toPrecision(3)))}; |d| up to ${formatNumber(largest)} ${surface.unit}`, 10, height - 10);
  canvas.dataset.drawn = String(cells.length);
}

function setUpSurfaceView() {
  const canvas = $('view3d');
  let drag = null;
  canvas.addEventListener('pointerdown', (event) => {
    if (!state.surface || event.button !== 0) return;
    drag = { x: event.clientX, y: event.clientY, yaw: view3d.yaw, pitch: view3d.pitch };
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    view3d.yaw = drag.yaw + (event.clientX - drag.x) * 0.01;
    view3d.pitch = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, drag.pitch + (event.clientY - drag.y) * 0.01));
    drawSurface3d();
  });
  const end = () => { drag = null; };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
  canvas.addEventListener('wheel', (event) => {
    if (!state.surface) return;
    event.preventDefault();
    view3d.zoom *= Math.exp(-event.deltaY * 0.0015);
    drawSurface3d();
  }, { passive: false });
  canvas.addEventListener('dblclick', () => { if (state.surface) resetView3d(); });
  $('reset-3d').addEventListener('click', () => { if (state.surface) resetView3d(); });
  window.addEventListener('resize', () => { if (state.surface) drawSurface3d(); });
}
