// hotmesh serve: the inspection page. Loads a CAD file (root folder or upload), lets the user
// pick faces, an axis (prefilled with the faces' own) and a deflection table, asks the service
// for the reconstructed curve (POST /api/curves) and draws in SVG the CAD curve, the FEM nodes,
// their deflections (amplified by a slider) and the reconstructed curve, with zoom, pan, a
// tooltip per node, the fit residual per node and download links. With "Surface (t, s)" ticked
// (by itself unless the ticked faces are one surface of revolution, as the service says)
// Reconstruct asks for the deflection field on the faces instead (POST /api/surfaces), which
// surface.js shows. Plain JavaScript, no library: users are often offline.
'use strict';

const SVG = 'http://www.w3.org/2000/svg';
const $ = (id) => document.getElementById(id);

const state = {
  model: null,       // answer of POST /api/models
  curve: null,       // answer of POST /api/curves or .../meridional
  surface: null,     // answer of POST /api/surfaces (surface.js), when that is on show
  modeChosen: null,  // the last question of POST /api/models/{id}/mode (surface.js), while it may be pending
  view: null,        // {x, y, w, h} in plot coordinates (y up)
  amplification: 1,
};

// ---- talking to the service --------------------------------------------------------------

async function api(method, path, body) {
  const init = { method, headers: {} };
  if (body instanceof FormData) {
    init.body = body;
  } else if (body !== undefined) {
    init.body = JSON.stringify(body);
    init.headers['Content-Type'] = 'application/json';
  }
  const response = await fetch(path, init);
  const json = await response.json();
  if (!response.ok) throw new Error(json.message || `${response.status} ${response.statusText}`);
  return json;
}

function showError(error) {
  const box = $('error');
  box.textContent = error ? String(error.message || error) : '';
  box.hidden = !error;
}

async function busy(button, work) {
  button.disabled = true;
  document.body.classList.add('busy');
  try {
    showError(null);
    await work();
  } catch (error) {
    showError(error);
  } finally {
    button.disabled = false;
    document.body.classList.remove('busy');
  }
}

// ---- numbers ------------------------------------------------------------------------------

/// The text every number on the page is shown with (tests format the API's values the same way).
function formatNumber(value) {
  if (value === null || value === undefined) return '–';
  if (typeof value !== 'number') return String(value);
  if (Number.isInteger(value)) return String(value);
  return String(Number(value.toPrecision(6)));
}

function pairText(p) { return `(${formatNumber(p[0])}, ${formatNumber(p[1])})`; }

// ---- the CAD model and its faces ---------------------------------------------------------

async function loadFiles() {
  const health = await api('GET', '/api/health');
  $('version').textContent = `version ${health.version}`;
  const files = await api('GET', '/api/files');
  const select = $('root-file');
  for (const file of files.files.filter((f) => f.kind === 'cad')) {
    const option = document.createElement('option');
    option.value = file.path;
    option.textContent = file.path;
    select.append(option);
  }
  select.disabled = !files.root;
  if (!files.root) select.title = 'start hotmesh serve with --root DIR to load files by path';
  document.body.dataset.ready = 'true';
}

async function loadCad() {
  const unit = $('unit').value;
  const path = $('root-file').value;
  const file = $('cad-file').files[0];
  if (path) {
    state.model = await api('POST', '/api/models', { path, unit });
  } else if (file) {
    const form = new FormData();
    form.append('file', file, file.name);
    form.append('unit', unit);
    state.model = await api('POST', '/api/models', form);
  } else {
    throw new Error('choose a CAD file from the root folder or upload one');
  }
  $('no-cad').checked = false;
  showFaces(state.model);
}

function showFaces(model) {
  $('model-info').textContent = `${model.name}: ${model.faces.length} faces, lengths in ${model.unit} (model ${model.model})`;
  const body = $('faces').querySelector('tbody');
  body.replaceChildren();
  for (const face of model.faces) {
    const row = document.createElement('tr');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.value = face.id;
    box.className = 'face';
    box.setAttribute('aria-label', `face ${face.id}`);
    box.addEventListener('change', () => {
      updateAxis();
      updateSurfaceMode();
    });
    const axis = document.createElement('span');
    axis.textContent = face.axis ? `(${face.axis.direction.map(formatNumber).join(', ')})` : '–';
    if (face.axis) {
      axis.title = `${face.axis.source} axis through (${face.axis.origin.map(formatNumber).join(', ')})` +
        ` along (${face.axis.direction.map(formatNumber).join(', ')})`;
    }
    const cells = [box, String(face.id), face.name || '–', face.kind, axis];
    for (const content of cells) {
      const cell = document.createElement('td');
      cell.append(content);
      row.append(cell);
    }
    body.append(row);
  }
  $('faces-box').hidden = false;
  $('show-meridional').disabled = false;
  updateAxis();
  updateSurfaceMode();
}

function selectedFaces() {
  return [...document.querySelectorAll('#faces input.face:checked')].map((box) => Number(box.value));
}

// ---- the axis -----------------------------------------------------------------------------

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

/// The same line written one way whatever the face says: the direction a unit vector whose
/// largest component is positive, the origin the point of the line nearest (0, 0, 0). So an
/// (r, z) table about the engine axis fits faces whose own axis points the other way or starts
/// elsewhere (a cylinder through (0, 0, 0.083) along (0, 0, -1) gives 0,0,0,0,0,1).
function canonicalAxis(axis, size) {
  const length = Math.hypot(...axis.direction);
  let d = axis.direction.map((x) => x / length);
  const largest = d.reduce((k, x, i) => (Math.abs(x) > Math.abs(d[k]) + 1e-12 ? i : k), 0);
  if (d[largest] < 0) d = d.map((x) => -x);
  const along = dot(axis.origin, d);
  const clean = (x, scale) => (Math.abs(x) < 1e-12 * scale ? 0 : Number(x.toPrecision(12)));
  return { origin: axis.origin.map((x, i) => clean(x - along * d[i], size)), direction: d.map((x) => clean(x, 1)) };
}

/// The model's size (the diagonal of its faces' bounds), the scale of axis comparisons.
function modelSize(model) {
  let size = 0;
  for (const face of model.faces) {
    if (face.bounds) size = Math.max(size, Math.hypot(...face.bounds.max.map((x, i) => x - face.bounds.min[i])));
  }
  return size > 0 ? size : 1;
}

/// The axis the ticked faces turn about, or why there is none.
function facesAxis() {
  const size = modelSize(state.model);
  const ticked = selectedFaces();
  const withAxis = state.model.faces.filter((f) => ticked.includes(f.id) && f.axis);
  if (ticked.length === 0) return { note: '' };
  if (withAxis.length === 0) return { note: 'the ticked faces have no axis of their own: type one for (r, z) tables' };
  const first = canonicalAxis(withAxis[0].axis, size);
  for (const face of withAxis.slice(1)) {
    const axis = canonicalAxis(face.axis, size);
    const apart = Math.hypot(...axis.origin.map((x, i) => x - first.origin[i]));
    if (Math.hypot(...cross(axis.direction, first.direction)) > 1e-6 || apart > 1e-6 * size) {
      return { note: `faces ${withAxis[0].id} and ${face.id} turn about different axes` };
    }
  }
  return { axis: first, note: `the axis of faces ${withAxis.map((f) => f.id).join(', ')}` };
}

/// Fills the axis field from the ticked faces, unless the user typed an axis of their own.
/// With "no CAD" the faces do not count: the field is the user's.
function updateAxis() {
  const field = $('axis');
  if (field.dataset.typed === 'true') return;
  const found = state.model && !$('no-cad').checked ? facesAxis() : { note: '' };
  field.value = found.axis ? [...found.axis.origin, ...found.axis.direction].map(String).join(',') : '';
  $('axis-note').textContent = found.note;
}

/// The axis field as the API's {origin, direction}; undefined when empty.
function axisRequest() {
  const text = $('axis').value.trim();
  if (text === '') return undefined;
  const numbers = text.split(/[\s,;]+/).map(Number);
  if (numbers.length !== 6 || !numbers.every(Number.isFinite) || numbers.slice(3).every((x) => x === 0)) {
    throw new Error(`axis: expected x,y,z,dx,dy,dz (a point and a non-zero direction, six numbers), got "${text}"`);
  }
  return { origin: numbers.slice(0, 3), direction: numbers.slice(3) };
}

async function showMeridional() {
  if (!state.model) throw new Error('load a CAD file first');
  const faces = selectedFaces();
  if (faces.length === 0) throw new Error('tick the faces of the boundary');
  const request = { faces };
  const axis = axisRequest();
  if (axis) request.axis = axis;
  setCurve(await api('POST', `/api/models/${state.model.model}/meridional`, request));
}

async function reconstruct() {
  const file = $('csv-file').files[0];
  if (!file) throw new Error('choose the CSV table of FEM nodes and deflections');
  const request = {
    csv: await file.text(),
    csv_name: file.name,
    degree: Number($('degree').value),
    form: $('form').value,
    drop_far_nodes: $('drop-far').checked,
  };
  const tolerance = $('tolerance').value;
  if (tolerance !== '') request.tolerance = Number(tolerance);
  await state.modeChosen;  // the service's choice for the faces ticked last
  if ($('surface-mode').checked) {
    delete request.form;  // surfaces take the displacement form
    await reconstructSurface(request);
    return;
  }
  const axis = axisRequest();
  if (axis) request.axis = axis;
  if (state.model && !$('no-cad').checked) {
    request.model = state.model.model;
    request.faces = selectedFaces();
    if (request.faces.length === 0) throw new Error('tick the faces of the boundary, or check "no CAD"');
  } else {
    request.unit = $('unit').value;
  }
  setCurve(await api('POST', '/api/curves', request));
}

// ---- the curve on show ------------------------------------------------------------------

function setCurve(curve) {
  state.curve = curve;
  state.surface = null;
  $('curve-box').hidden = false;
  $('surface-box').hidden = true;
  $('downloads-what').textContent = 'Deformed curve:';
  const slider = $('amplification');
  const automatic = curve.amplification || 1;
  slider.disabled = curve.kind !== 'reconstructed';
  slider.value = String(Math.log10(automatic));
  setAmplification(automatic);
  showSummary(curve);
  showDownloads(curve);
  fitView();
  drawResiduals(curve);
  fillNodeTable(curve);
}

function setAmplification(value) {
  state.amplification = value;
  const output = $('amplification-value');
  output.textContent = `×${formatNumber(Number(value.toPrecision(3)))}`;
  output.dataset.value = String(value);
}

function showSummary(curve) {
  const summary = curve.summary || {};
  for (const dd of document.querySelectorAll('#summary dd')) {
    const key = dd.dataset.key;
    let value = summary[key];
    if (key === 'rejected_nodes') value = value ? value.length : undefined;
    dd.textContent = value === undefined ? '–' : formatNumber(value);
    if (value === undefined) delete dd.dataset.value;
    else dd.dataset.value = JSON.stringify(value);
  }
}

function showDownloads(curve) {
  const links = { step: 'download-step', iges: 'download-iges', csv: 'download-csv' };
  for (const [format, id] of Object.entries(links)) {
    const link = $(id);
    const href = curve.downloads[format];
    if (href) {
      link.href = href;
      link.setAttribute('download', '');
    } else {
      link.removeAttribute('href');
    }
    link.classList.toggle('disabled', !href);
  }
}

/// Plot coordinates of a curve-plane pair: meridional (r, z) shows z across and r up.
function toPlot(curve, p) { return curve.frame === 'rz' ? [p[1], p[0]] : [p[0], p[1]]; }

/// The reconstructed curve with its deflection amplified `a` times, r(t) + a (c(t) - r(t)).
function amplifiedCurve(curve, a) {
  return curve.deformed.samples.map((s, i) => {
    const u = curve.undeformed.samples[i];
    return toPlot(curve, [u[1] + a * (s[1] - u[1]), u[2] + a * (s[2] - u[2])]);
  });
}

/// Where a node's deflection arrow ends, Q + a δ.
function arrowTip(curve, node, a) {
  return toPlot(curve, [node.point[0] + a * node.deflection[0], node.point[1] + a * node.deflection[1]]);
}

/// Everything drawn at the current amplification.
function plotPoints(curve) {
  const a = state.amplification;
  const points = curve.undeformed.samples.map((s) => toPlot(curve, [s[1], s[2]]));
  if (curve.deformed) points.push(...amplifiedCurve(curve, a));
  for (const node of curve.nodes) points.push(toPlot(curve, node.point), arrowTip(curve, node, a));
  return points;
}

function fitView() {
  const curve = state.curve;
  if (!curve) return;
  const points = plotPoints(curve);
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const [x, y] of points) {
    x0 = Math.min(x0, x); x1 = Math.max(x1, x);
    y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  }
  const box = $('plot').getBoundingClientRect();
  const aspect = box.height / Math.max(box.width, 1);
  let w = Math.max(x1 - x0, 1e-12), h = Math.max(y1 - y0, 1e-12);
  if (h / w > aspect) w = h / aspect; else h = w * aspect;
  w *= 1.1; h *= 1.1;
  state.view = { x: (x0 + x1) / 2 - w / 2, y: (y0 + y1) / 2 - h / 2, w, h };
  draw();
}

// ---- drawing ----------------------------------------------------------------------------

function element(name, attributes, parent) {
  const e = document.createElementNS(SVG, name);
  for (const [key, value] of Object.entries(attributes)) e.setAttribute(key, value);
  if (parent) parent.append(e);
  return e;
}

/// SVG y grows downwards: world (x, y) is drawn at (x, -y).
function pathData(points) {
  return points.map(([x, y], i) => `${i ? 'L' : 'M'}${x},${-y}`).join('');
}

function pixelSize() {
  const box = $('plot').getBoundingClientRect();
  return state.view.w / Math.max(box.width, 1);
}

function draw() {
  const curve = state.curve;
  const view = state.view;
  hideTooltip();  // its node marker is about to be replaced (new curve, zoom, pan, amplification)
  const svg = $('plot');
  svg.setAttribute('viewBox', `${view.x} ${-(view.y + view.h)} ${view.w} ${view.h}`);
  drawGrid();
  const world = $('world');
  world.replaceChildren();
  if (!curve) return;
  const px = pixelSize();
  const a = state.amplification;
  const undeformed = curve.undeformed.samples.map((s) => toPlot(curve, [s[1], s[2]]));
  element('path', { d: pathData(undeformed), class: 'cad-curve', id: 'cad-curve' }, world);
  if (curve.deformed) {
    element('path', { d: pathData(amplifiedCurve(curve, a)), class: 'deformed-curve', id: 'deformed-curve' }, world);
  }
  const arrows = element('g', { id: 'arrows' }, world);
  const nodes = element('g', { id: 'node-markers' }, world);
  for (const node of curve.nodes) {
    const [x, y] = toPlot(curve, node.point);
    const [tx, ty] = arrowTip(curve, node, a);
    if (Math.hypot(tx - x, ty - y) > 0) {
      element('line', { x1: x, y1: -y, x2: tx, y2: -ty, class: 'arrow', 'marker-end': 'url(#arrow-head)' }, arrows);
    }
    const marker = element('circle', {
      cx: x, cy: -y, r: 4 * px, class: node.rejected ? 'node rejected' : 'node', 'data-index': node.index,
    }, nodes);
    marker.addEventListener('pointerenter', (event) => showTooltip(node, event));
    marker.addEventListener('pointerleave', hideTooltip);
  }
}

/// Grid lines at 1, 2 or 5 times a power of ten, labelled in the plot's units.
function drawGrid() {
  const grid = $('grid');
  grid.replaceChildren();
  const view = state.view;
  const px = pixelSize();
  const raw = 80 * px;
  const decade = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * decade).find((s) => s >= raw);
  const label = state.curve && state.curve.frame === 'rz' ? ['z', 'r'] : ['x', 'y'];
  const unit = state.curve ? state.curve.unit : '';
  const text = (x, y, content, anchor) => {
    const t = element('text', { x, y, 'font-size': 11 * px, class: 'grid-label', 'text-anchor': anchor }, grid);
    t.textContent = content;
  };
  for (let x = Math.ceil(view.x / step) * step; x <= view.x + view.w; x += step) {
    element('line', { x1: x, y1: -(view.y + view.h), x2: x, y2: -view.y, class: 'grid-line' }, grid);
    text(x + 3 * px, -view.y - 4 * px, formatNumber(Number(x.toPrecision(12))), 'start');
  }
  for (let y = Math.ceil(view.y / step) * step; y <= view.y + view.h; y += step) {
    element('line', { x1: view.x, y1: -y, x2: view.x + view.w, y2: -y, class: 'grid-line' }, grid);
    text(view.x + 3 * px, -y - 3 * px, formatNumber(Number(y.toPrecision(12))), 'start');
  }
  text(view.x + view.w - 6 * px, -view.y - 20 * px, `${label[0]} [${unit}] →`, 'end');
  text(view.x + 6 * px, -(view.y + view.h) + 14 * px, `↑ ${label[1]} [${unit}]`, 'start');
}

function showTooltip(node, event) {
  const tip = $('tooltip');
  const lines = [
    ['node', node.label],
    ['Q', pairText(node.point)],
    ['δ', pairText(node.deflection)],
    ['t', formatNumber(node.parameter)],
    ['distance to CAD', formatNumber(node.distance)],
    ['residual', node.rejected ? 'left out' : formatNumber(node.residual)],
  ];
  placeTooltip(tip, lines, $('plot-box'), node, event);
  highlightRow(node.index);
}

// A tooltip of key/value rows for `node`, next to the pointer inside `box` (the curve's plot
// and the surface's map share it).
function placeTooltip(tip, lines, box, node, event) {
  tip.replaceChildren();
  for (const [key, value] of lines) {
    const row = document.createElement('div');
    const k = document.createElement('span');
    k.className = 'key';
    k.textContent = key;
    const v = document.createElement('span');
    v.className = 'value';
    v.dataset.key = key;
    v.textContent = value;
    row.append(k, v);
    tip.append(row);
  }
  const rect = box.getBoundingClientRect();
  tip.style.left = `${event.clientX - rect.left + 12}px`;
  tip.style.top = `${event.clientY - rect.top + 12}px`;
  tip.hidden = false;
  tip.dataset.index = node.index;
}

function hideTooltip() {
  $('tooltip').hidden = true;
  highlightRow(null);
}

function highlightRow(index) {
  for (const row of document.querySelectorAll('#nodes tbody tr')) {
    row.classList.toggle('highlight', Number(row.dataset.index) === index);
  }
}

// ---- residual per node -------------------------------------------------------------------

/// Bars of log10(residual) per node, in order along the curve; the axis spans the data.
function drawResiduals(curve) {
  const svg = $('residuals');
  svg.replaceChildren();
  const nodes = curve.nodes.filter((n) => !n.rejected).sort((p, q) => p.parameter - q.parameter);
  if (nodes.length === 0) return;
  const width = 1000, height = 160, left = 60, bottom = 20;
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const positive = nodes.map((n) => n.residual).filter((r) => r > 0);
  const logs = nodes.map((n) => (n.residual > 0 ? Math.log10(n.residual) : -Infinity));
  const lo = positive.length ? Math.floor(Math.max(Math.log10(Math.min(...positive)), -20)) - 1 : -17;
  const hi = Math.max(positive.length ? Math.ceil(Math.log10(Math.max(...positive))) : -15, lo + 1);
  const y = (v) => height - bottom - ((Math.max(v, lo) - lo) / (hi - lo)) * (height - bottom - 10);
  for (let e = lo; e <= hi; e += Math.max(1, Math.round((hi - lo) / 4))) {
    element('line', { x1: left, x2: width, y1: y(e), y2: y(e), class: 'grid-line-px' }, svg);
    element('text', { x: left - 6, y: y(e) + 4, 'text-anchor': 'end', class: 'bar-label' }, svg).textContent = `1e${e}`;
  }
  const slot = (width - left) / nodes.length;
  nodes.forEach((node, i) => {
    const top = Math.min(y(logs[i]), height - bottom - 1);
    const bar = element('rect', {
      x: left + i * slot + slot * 0.1, y: top, width: Math.max(slot * 0.8, 0.5), height: height - bottom - top,
      class: 'bar', 'data-index': node.index,
    }, svg);
    element('title', {}, bar).textContent = `${node.label}: residual ${formatNumber(node.residual)}`;
  });
  const exact = positive.length === 0 ? ': every residual is 0, the curve passes through every node exactly' : '';
  element('text', { x: left, y: height - 4, class: 'bar-label' }, svg).textContent =
    `${nodes.length} nodes in order along the curve (residual |c(t_j) − (Q_j + δ_j)|, log scale)${exact}`;
}

function fillNodeTable(curve) {
  const body = $('nodes').querySelector('tbody');
  body.replaceChildren();
  for (const node of curve.nodes.slice(0, 5000)) {
    const row = document.createElement('tr');
    row.dataset.index = node.index;
    const residual = node.rejected ? 'left out' : formatNumber(node.residual);
    for (const value of [node.label, formatNumber(node.parameter), formatNumber(node.distance), residual]) {
      const cell = document.createElement('td');
      cell.textContent = value;
      row.append(cell);
    }
    body.append(row);
  }
}

// ---- zoom and pan ------------------------------------------------------------------------

function worldAt(event) {
  const box = $('plot').getBoundingClientRect();
  const v = state.view;
  return [v.x + ((event.clientX - box.left) / box.width) * v.w, v.y + v.h - ((event.clientY - box.top) / box.height) * v.h];
}

function setUpView() {
  const svg = $('plot');
  svg.addEventListener('wheel', (event) => {
    if (!state.view) return;
    event.preventDefault();
    const [wx, wy] = worldAt(event);
    const factor = Math.exp(event.deltaY * 0.0015);
    const v = state.view;
    state.view = { x: wx - (wx - v.x) * factor, y: wy - (wy - v.y) * factor, w: v.w * factor, h: v.h * factor };
    draw();
  }, { passive: false });
  let drag = null;
  svg.addEventListener('pointerdown', (event) => {
    if (!state.view || event.button !== 0) return;
    drag = { x: event.clientX, y: event.clientY, view: { ...state.view } };
    svg.setPointerCapture(event.pointerId);
  });
  svg.addEventListener('pointermove', (event) => {
    if (state.view) {
      const [wx, wy] = worldAt(event);
      $('cursor').textContent = `(${formatNumber(wx)}, ${formatNumber(wy)})`;
    }
    if (!drag) return;
    const box = svg.getBoundingClientRect();
    const dx = ((event.clientX - drag.x) / box.width) * drag.view.w;
    const dy = ((event.clientY - drag.y) / box.height) * drag.view.h;
    state.view = { ...drag.view, x: drag.view.x - dx, y: drag.view.y + dy };
    draw();
  });
  const end = () => { drag = null; };
  svg.addEventListener('pointerup', end);
  svg.addEventListener('pointercancel', end);
  svg.addEventListener('dblclick', fitView);
  $('fit-view').addEventListener('click', fitView);
  window.addEventListener('resize', () => { if (state.curve && !state.surface) fitView(); });
}

// ---- start -------------------------------------------------------------------------------

function start() {
  $('load-cad').addEventListener('click', (e) => busy(e.target, loadCad));
  $('show-meridional').addEventListener('click', (e) => busy(e.target, showMeridional));
  $('reconstruct').addEventListener('click', (e) => busy(e.target, reconstruct));
  $('no-cad').addEventListener('change', updateAxis);
  $('axis').addEventListener('input', (event) => {
    const typed = event.target.value.trim() !== '';
    event.target.dataset.typed = String(typed);
    $('axis-note').textContent = typed ? 'your own axis' : '';
  });
  $('axis').addEventListener('change', updateSurfaceMode);  // a typed axis, complete
  $('amplification').addEventListener('input', (event) => {
    setAmplification(Math.pow(10, Number(event.target.value)));
    if (state.surface) drawSurface3d();
    else if (state.view) draw();
  });
  $('surface-mode').addEventListener('change', (event) => { $('form').disabled = event.target.checked; });
  setUpView();
  setUpSurfaceView();
  loadFiles().catch(showError);
}

document.addEventListener('DOMContentLoaded', start);
