// bcot review: the page of one sequence (and annotation). Plain JS, no framework, no network
// beyond this server; the timeline and the trajectory are drawn as SVG by hand. The page marks its state on <body>
// for tests and scripts: data-frame (shown frame), data-loaded-frame (frame whose images have
// all loaded), data-ready (sequence and quality read).
'use strict';

const SVG = 'http://www.w3.org/2000/svg';
const COLORS = ['#2a6', '#36c', '#c63', '#939', '#088', '#a80'];

const state = {
  sequence: null,   // /api/sequence
  quality: null,    // /api/quality
  trajectory: null, // /api/trajectory
  mask: false,      // tint the model's silhouette on the images
  frame: 0,
  playing: false,
  views: [],        // {camera, img, viewport, label, zoom, x, y}
};

function $(id) { return document.getElementById(id); }

async function getJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(url + ': ' + response.status + ' ' + await response.text());
  return response.json();
}

function el(tag, attributes, text) {
  const node = tag.startsWith('svg:') ? document.createElementNS(SVG, tag.slice(4))
                                       : document.createElement(tag);
  for (const [key, value] of Object.entries(attributes || {})) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

// --- views: images side by side, zoom and pan ------------------------------------------------

function applyTransform(view) {
  view.img.style.transform = `translate(${view.x}px, ${view.y}px) scale(${view.zoom})`;
  view.viewport.classList.toggle('zoomed', view.zoom > 1);
  view.label.textContent = view.zoom > 1 ? `${view.zoom.toFixed(1)}×` : '';
}

function addZoomPan(view) {
  const viewport = view.viewport;
  viewport.addEventListener('wheel', (event) => {
    event.preventDefault();
    const rect = viewport.getBoundingClientRect();
    const px = event.clientX - rect.left, py = event.clientY - rect.top;
    const zoom = Math.min(8, Math.max(1, view.zoom * (event.deltaY < 0 ? 1.25 : 0.8)));
    // Keep the point under the cursor fixed.
    view.x = px - (px - view.x) * zoom / view.zoom;
    view.y = py - (py - view.y) * zoom / view.zoom;
    view.zoom = zoom;
    if (zoom === 1) view.x = view.y = 0;
    applyTransform(view);
  }, {passive: false});
  let drag = null;
  viewport.addEventListener('pointerdown', (event) => {
    drag = {x: event.clientX - view.x, y: event.clientY - view.y};
    viewport.setPointerCapture(event.pointerId);
  });
  viewport.addEventListener('pointermove', (event) => {
    if (!drag || view.zoom === 1) return;
    view.x = event.clientX - drag.x;
    view.y = event.clientY - drag.y;
    applyTransform(view);
  });
  viewport.addEventListener('pointerup', () => { drag = null; });
  viewport.addEventListener('dblclick', () => {
    view.zoom = 1; view.x = view.y = 0;
    applyTransform(view);
  });
}

function buildViews() {
  const container = $('views');
  for (const camera of state.sequence.cameras) {
    const box = el('div', {class: 'view'});
    const title = el('h3', {}, `${camera.name} (${camera.width}×${camera.height}) `);
    const label = el('span', {class: 'zoom'});
    title.appendChild(label);
    const viewport = el('div', {class: 'viewport'});
    const img = el('img', {alt: camera.name, 'data-camera': camera.name, draggable: 'false'});
    viewport.appendChild(img);
    box.append(title, viewport);
    container.appendChild(box);
    const view = {camera: camera.name, img, viewport, label, zoom: 1, x: 0, y: 0, frame: -1};
    img.addEventListener('load', imageDone);
    img.addEventListener('error', imageDone);
    addZoomPan(view);
    state.views.push(view);
  }
}

// Whether every view shows the image of the current frame (loaded or failed).
function frameComplete() {
  return state.views.every((view) => view.frame === state.frame && view.img.complete);
}

function imageDone() {
  if (!frameComplete()) return;
  document.body.dataset.loadedFrame = String(state.frame);
  if (state.playing) setTimeout(step, 30, 1);
}

// --- frame switching --------------------------------------------------------------------------

function showFrame(frame) {
  const count = state.sequence.num_frames;
  frame = Math.max(0, Math.min(count - 1, Math.round(frame)));
  state.frame = frame;
  document.body.dataset.frame = String(frame);
  $('frame-number').textContent = String(frame);
  $('slider').value = String(frame);
  delete document.body.dataset.loadedFrame;  // set again when the new images have loaded
  for (const view of state.views) {
    view.frame = frame;
    view.img.src = `api/frame/${frame}/view/${encodeURIComponent(view.camera)}.jpg` +
        (state.mask ? '?mask=1' : '');
  }
  moveCursor();
  loadDiagnostics(frame);
  loadPose(frame);
  // The address names the frame shown (#frame=N), so it can be shared or reopened there.
  history.replaceState(null, '', `#frame=${frame}`);
}

// The frame the address asks for (#frame=N, as `bcot review --frame N` prints it), else 0.
function frameFromAddress() {
  const match = /^#frame=(\d+)$/.exec(window.location.hash);
  return match ? Number(match[1]) : 0;
}

function step(delta) {
  const count = state.sequence.num_frames;
  if (state.playing && state.frame + delta >= count) {
    setPlaying(false);
    return;
  }
  showFrame(state.frame + delta);
}

function setPlaying(playing) {
  state.playing = playing;
  $('play').textContent = playing ? '❚❚ pause' : '▶ play';
  if (!playing || !frameComplete()) return;
  if (state.frame + 1 >= state.sequence.num_frames) {
    showFrame(0);
  } else {
    step(1);
  }
}

async function loadDiagnostics(frame) {
  const diagnostics = await getJson(`api/frame/${frame}/diagnostics`);
  if (frame !== state.frame) return;
  $('diagnostics-frame').textContent = String(frame);
  const table = $('diagnostics');
  table.replaceChildren();
  if (!diagnostics.available) {
    table.appendChild(el('tr', {}, 'no frames.csv in the annotation'));
    return;
  }
  for (const [key, value] of Object.entries(diagnostics.values)) {
    const row = el('tr');
    row.append(el('td', {}, key), el('td', {}, value));
    table.appendChild(row);
  }
}

// --- timeline -----------------------------------------------------------------------------------

const MARGIN = {left: 44, right: 10, top: 10, bottom: 24};

function timelineScale(svg = $('timeline')) {
  const width = svg.clientWidth || 800, height = svg.clientHeight || 220;
  const count = state.sequence.num_frames;
  const plotWidth = width - MARGIN.left - MARGIN.right;
  const x = (frame) => MARGIN.left + (count > 1 ? frame / (count - 1) : 0.5) * plotWidth;
  const toFrame = (px) => (px - MARGIN.left) / plotWidth * (count - 1);
  return {width, height, x, toFrame, plotWidth};
}

function drawTimeline() {
  const svg = $('timeline');
  svg.replaceChildren();
  const quality = state.quality;
  const scale = timelineScale();
  const {width, height, x} = scale;
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const bottom = height - MARGIN.bottom;
  let max = quality.available ? quality.threshold_px * 1.5 : 1;
  if (quality.available) {
    for (const view of quality.views) {
      for (const e of view.error_px) if (e !== null) max = Math.max(max, e);
    }
  }
  const y = (value) => bottom - value / max * (bottom - MARGIN.top);
  const half = Math.max(1, scale.plotWidth / Math.max(1, state.sequence.num_frames - 1) / 2);
  if (quality.available) {
    for (const view of quality.views) {
      for (const frame of view.unverifiable_frames) {
        svg.appendChild(el('svg:rect', {class: 'unverifiable', x: x(frame) - half, y: MARGIN.top,
                                        width: 2 * half, height: bottom - MARGIN.top}));
      }
    }
    for (const frame of quality.bad_frames) {
      const band = el('svg:rect', {class: 'bad', x: x(frame) - half, y: MARGIN.top,
                                   width: 2 * half, height: bottom - MARGIN.top,
                                   'data-frame': frame});
      band.appendChild(el('svg:title', {}, `frame ${frame}: bad`));
      svg.appendChild(band);
    }
    svg.appendChild(el('svg:line', {class: 'threshold', x1: MARGIN.left, x2: width - MARGIN.right,
                                    y1: y(quality.threshold_px), y2: y(quality.threshold_px)}));
    quality.views.forEach((view, v) => {
      let path = '';
      view.error_px.forEach((e, frame) => {
        if (e === null) return;
        path += `${path && view.error_px[frame - 1] !== null ? 'L' : 'M'}${x(frame)},${y(e)}`;
      });
      svg.appendChild(el('svg:path', {d: path, fill: 'none', stroke: COLORS[v % COLORS.length],
                                      'stroke-width': 1.5}));
    });
  }
  // Axes: error ticks on the left, frame ticks below.
  svg.appendChild(el('svg:line', {class: 'axis', x1: MARGIN.left, x2: MARGIN.left,
                                  y1: MARGIN.top, y2: bottom}));
  svg.appendChild(el('svg:line', {class: 'axis', x1: MARGIN.left, x2: width - MARGIN.right,
                                  y1: bottom, y2: bottom}));
  for (let i = 0; i <= 4; ++i) {
    const value = max * i / 4;
    svg.appendChild(el('svg:text', {x: 4, y: y(value) + 4}, value.toFixed(1)));
  }
  const count = state.sequence.num_frames;
  const tickStep = niceStep(count / Math.max(2, Math.floor(width / 70)));
  for (let frame = 0; frame < count; frame += tickStep) {
    svg.appendChild(el('svg:text', {x: x(frame) - 4, y: height - 6}, String(frame)));
  }
  svg.appendChild(el('svg:line', {class: 'cursor', id: 'cursor', y1: MARGIN.top, y2: bottom}));
  moveCursor();
}

function niceStep(raw) {
  const steps = [1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000, 2000, 5000];
  return steps.find((s) => s >= raw) || 10000;
}

function moveCursor() {
  if (!state.sequence) return;
  for (const [cursorId, svgId] of [['cursor', 'timeline'], ['rotation-cursor', 'rotation'],
                                   ['translation-cursor', 'translation']]) {
    const cursor = $(cursorId);
    if (!cursor) continue;
    const px = timelineScale($(svgId)).x(state.frame);
    cursor.setAttribute('x1', px);
    cursor.setAttribute('x2', px);
  }
}

// --- editing --------------------------------------------------------------------------------

async function post(url) {
  const response = await fetch(url, {method: 'POST'});
  const text = await response.text();
  if (!response.ok) throw new Error(text.trim());
  return JSON.parse(text);
}

function describeEdit(pose) {
  document.body.dataset.edits = String(pose.edits);
  $('edit-status').textContent = pose.edits ?
      `Frame ${pose.frame}: ${pose.edits} edit(s), contour in yellow. Set it as a keyframe to ` +
      'keep it.' : `Frame ${pose.frame}: the annotated pose (green).`;
}

async function edit(action) {
  try {
    describeEdit(await action());
    showFrame(state.frame);
  } catch (error) {
    $('edit-status').textContent = String(error.message);
  }
}

function bindEditing() {
  const select = $('edit-camera');
  for (const camera of state.sequence.cameras) {
    select.appendChild(el('option', {value: camera.name}, camera.name));
  }
  for (const button of document.querySelectorAll('[data-nudge]')) {
    button.addEventListener('click', () => {
      const [key, sign] = button.dataset.nudge.split(':');
      const amount = Number(sign) * Number($('edit-step').value);
      edit(() => post(`api/frame/${state.frame}/nudge?camera=` +
                      `${encodeURIComponent(select.value)}&${key}=${amount}`));
    });
  }
  $('undo').addEventListener('click', () => edit(() => post(`api/frame/${state.frame}/undo`)));
  $('refine').addEventListener('click', () => {
    $('edit-status').textContent = `Refining frame ${state.frame} …`;
    edit(() => post(`api/frame/${state.frame}/refine`));
  });
  $('keyframe').addEventListener('click', async () => {
    try {
      const written = await post(`api/frame/${state.frame}/keyframe`);
      document.body.dataset.keyframe = String(written.frame);
      $('edit-status').textContent = `Keyframe ${written.frame} written to ${written.path}. ` +
          `Re-annotate around it with: ${written.command}`;
    } catch (error) {
      $('edit-status').textContent = String(error.message);
    }
  });
}

async function loadPose(frame) {
  if (!state.sequence.contour) return;
  const pose = await getJson(`api/frame/${frame}/pose`);
  if (frame === state.frame) describeEdit(pose);
}

// --- trajectory -------------------------------------------------------------------------------

// One chart of the trajectory: `series` = [{name, values}] over the frames, keyframes as dashed
// vertical lines, a cursor at the shown frame; values are drawn against their common range.
function drawSeries(svg, series, cursorId) {
  svg.replaceChildren();
  const scale = timelineScale(svg);
  const {width, height, x} = scale;
  svg.setAttribute('viewBox', `0 0 ${width} ${height}`);
  const bottom = height - MARGIN.bottom;
  let lo = Infinity, hi = -Infinity;
  for (const s of series) {
    for (const v of s.values) {
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    }
  }
  if (!(hi > lo)) {
    lo -= 1;
    hi += 1;
  }
  const y = (value) => bottom - (value - lo) / (hi - lo) * (bottom - MARGIN.top);
  for (const frame of state.trajectory.keyframes) {
    const line = el('svg:line', {class: 'keyframe', x1: x(frame), x2: x(frame), y1: MARGIN.top,
                                 y2: bottom, 'data-frame': frame});
    line.appendChild(el('svg:title', {}, `keyframe ${frame}`));
    svg.appendChild(line);
  }
  series.forEach((s, k) => {
    const path = s.values.map((v, frame) => `${frame ? 'L' : 'M'}${x(frame)},${y(v)}`).join('');
    svg.appendChild(el('svg:path', {d: path, fill: 'none', stroke: COLORS[k % COLORS.length],
                                    'stroke-width': 1.5, 'data-series': s.name}));
  });
  svg.appendChild(el('svg:line', {class: 'axis', x1: MARGIN.left, x2: MARGIN.left,
                                  y1: MARGIN.top, y2: bottom}));
  svg.appendChild(el('svg:line', {class: 'axis', x1: MARGIN.left, x2: width - MARGIN.right,
                                  y1: bottom, y2: bottom}));
  for (let i = 0; i <= 4; ++i) {
    const value = lo + (hi - lo) * i / 4;
    svg.appendChild(el('svg:text', {x: 4, y: y(value) + 4}, value.toFixed(1)));
  }
  svg.appendChild(el('svg:line', {class: 'cursor', id: cursorId, y1: MARGIN.top, y2: bottom}));
}

function drawTrajectory() {
  const trajectory = state.trajectory;
  $('trajectory-section').hidden = !trajectory.available;
  if (!trajectory.available) return;
  const centre = trajectory.centre_mm;
  const relative = (values) => values.map((v) => v - values[0]);
  drawSeries($('rotation'), [{name: 'rotation', values: trajectory.rotation_deg}],
             'rotation-cursor');
  drawSeries($('translation'), [{name: 'x', values: relative(centre.x)},
                                {name: 'y', values: relative(centre.y)},
                                {name: 'z', values: relative(centre.z)}],
             'translation-cursor');
  const keyframes = trajectory.keyframes.length ?
      `keyframes (dashed): ${trajectory.keyframes.join(', ')}` : 'no keyframes';
  $('trajectory-note').textContent = 'Rotation from frame 0 (deg) and the object centre\'s ' +
      'displacement from frame 0 along the rig axes (mm; x, y, z in the colours of the first ' +
      `three views); ${keyframes}. Click to jump to a frame.`;
  moveCursor();
}

function describeQuality() {
  const quality = state.quality;
  const note = $('timeline-note');
  const legend = $('legend');
  if (!quality.available) {
    note.textContent = 'No quality.json in the annotation: no error timeline.';
    $('bad-frames').textContent = 'unknown (no quality.json)';
    return;
  }
  note.textContent = `The ${quality.statistic} reprojection error (px) per view; dashed: the ` +
      `rejection threshold ${quality.threshold_px} px; red bands: bad frames; grey: cannot ` +
      'be told. Click to jump to a frame.';
  quality.views.forEach((view, v) => {
    const item = el('span', {}, `— ${view.name} (${view.bad_frames.length} bad)`);
    item.style.color = COLORS[v % COLORS.length];
    legend.appendChild(item);
  });
  const list = $('bad-frames');
  list.replaceChildren();
  if (quality.bad_frames.length === 0) list.textContent = 'none';
  for (const frame of quality.bad_frames) {
    const button = el('button', {type: 'button', 'data-frame': frame}, String(frame));
    button.addEventListener('click', () => showFrame(frame));
    list.appendChild(button);
  }
}

// --- start ----------------------------------------------------------------------------------

function bindControls() {
  $('slider').addEventListener('input', (event) => showFrame(Number(event.target.value)));
  $('prev').addEventListener('click', () => step(-1));
  $('next').addEventListener('click', () => step(1));
  $('play').addEventListener('click', () => setPlaying(!state.playing));
  $('timeline').addEventListener('click', (event) => {
    const rect = $('timeline').getBoundingClientRect();
    showFrame(timelineScale().toFrame(event.clientX - rect.left));
  });
  document.addEventListener('keydown', (event) => {
    if (event.target.tagName === 'INPUT' && event.key !== ' ') return;
    const moves = {ArrowLeft: -1, ArrowRight: 1, PageUp: -10, PageDown: 10};
    if (event.key in moves) {
      showFrame(state.frame + moves[event.key]);
    } else if (event.key === 'Home') {
      showFrame(0);
    } else if (event.key === 'End') {
      showFrame(state.sequence.num_frames - 1);
    } else if (event.key === ' ') {
      setPlaying(!state.playing);
    } else {
      return;
    }
    event.preventDefault();
  });
  for (const id of ['rotation', 'translation']) {
    $(id).addEventListener('click', (event) => {
      const rect = $(id).getBoundingClientRect();
      showFrame(timelineScale($(id)).toFrame(event.clientX - rect.left));
    });
  }
  $('mask').addEventListener('change', (event) => {
    state.mask = event.target.checked;
    showFrame(state.frame);
  });
  window.addEventListener('resize', () => {
    drawTimeline();
    drawTrajectory();
  });
}

async function start() {
  try {
    [state.sequence, state.quality, state.trajectory] = await Promise.all(
        [getJson('api/sequence'), getJson('api/quality'), getJson('api/trajectory')]);
  } catch (error) {
    $('source').textContent = String(error);
    return;
  }
  const sequence = state.sequence;
  $('source').textContent = `Sequence ${sequence.sequence}, ${sequence.num_frames} frames, ` +
      `${sequence.cameras.length} views` +
      (sequence.annotation ? `; annotation ${sequence.annotation}` : '');
  $('contour-note').hidden = sequence.contour;
  $('slider').max = String(sequence.num_frames - 1);
  $('frame-count').textContent = String(sequence.num_frames - 1);
  buildViews();
  bindControls();
  describeQuality();
  drawTimeline();
  drawTrajectory();
  $('mask-label').hidden = !sequence.contour;
  $('edit-section').hidden = !sequence.contour;
  if (sequence.contour) bindEditing();
  showFrame(frameFromAddress());
  document.body.dataset.ready = 'yes';
}

start();
