// bcot review: the page of one sequence (and annotation). Plain JS, no framework, no network
// beyond this server; the charts are dygraphs (Debian's libjs-dygraphs, served by bcot review).
// The page marks its state on <body> for tests and scripts: data-frame (shown frame),
// data-loaded-frame (frame whose images have all loaded), data-ready (sequence and quality read),
// data-edits, data-keyframe, data-job (state of the last job of this page: running, done,
// failed), data-init-candidates, data-init-saved.
'use strict';

const COLORS = ['#2a6', '#36c', '#c63', '#939', '#088', '#a80'];

const state = {
  sequence: null,   // /api/sequence
  quality: null,    // /api/quality
  trajectory: null, // /api/trajectory
  mask: false,      // tint the model's silhouette on the images
  frame: 0,
  playing: false,
  views: [],        // {camera, img, viewport, label, zoom, x, y}
  charts: {},       // id -> Dygraph
  clicks: {},       // initialisation: camera -> [x, y] (image pixels) on frame clickFrame
  clickFrame: -1,
  candidate: -1,    // initialisation: the candidate drawn on the views
  init: null,       // /api/init after a search
};

function $(id) { return document.getElementById(id); }

async function getJson(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(url + ': ' + response.status + ' ' + await response.text());
  return response.json();
}

function el(tag, attributes, text) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes || {})) node.setAttribute(key, value);
  if (text !== undefined) node.textContent = text;
  return node;
}

// --- views: images side by side, zoom and pan ------------------------------------------------

function applyTransform(view) {
  view.img.style.transform = `translate(${view.x}px, ${view.y}px) scale(${view.zoom})`;
  view.viewport.classList.toggle('zoomed', view.zoom > 1);
  view.label.textContent = view.zoom > 1 ? `${view.zoom.toFixed(1)}×` : '';
  placeMarker(view);
}

// Whether drags and the wheel on the views edit the pose ("drag edits the pose"), not the
// zoom and pan.
function dragEdits() {
  return !$('edit-section').hidden && $('edit-drag').checked;
}

// A drag on `view` by (dx, dy) client pixels as an edit of the frame's pose in that view: a move
// of the object's centre by as many image pixels, or with shift a turn about the view's axes
// (0.25° per image pixel) that carries the object's near side along with the pointer.
function dragEdit(view, dx, dy, turn) {
  const scale = view.img.naturalWidth / (view.img.clientWidth * view.zoom);  // image px per px
  const [u, v] = [dx * scale, dy * scale];
  const change = turn ? `ry=${(-0.25 * u).toFixed(3)}&rx=${(0.25 * v).toFixed(3)}`
                      : `dx=${u.toFixed(3)}&dy=${v.toFixed(3)}`;
  edit(() => post(`api/frame/${state.frame}/nudge?camera=${encodeURIComponent(view.camera)}` +
                  `&${change}`));
}

function addZoomPan(view) {
  const viewport = view.viewport;
  viewport.addEventListener('wheel', (event) => {
    event.preventDefault();
    if (dragEdits()) {  // nearer (wheel up) or farther by one step (mm)
      const dz = Math.sign(event.deltaY) * Number($('edit-step').value);
      if (dz) {
        edit(() => post(`api/frame/${state.frame}/nudge?camera=` +
                        `${encodeURIComponent(view.camera)}&dz=${dz}`));
      }
      return;
    }
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
    drag = {x: event.clientX - view.x, y: event.clientY - view.y, moved: false,
            startX: event.clientX, startY: event.clientY};
    viewport.setPointerCapture(event.pointerId);
  });
  viewport.addEventListener('pointermove', (event) => {
    if (!drag) return;
    drag.moved ||= Math.hypot(event.clientX - drag.startX, event.clientY - drag.startY) > 3;
    if (view.zoom === 1 || dragEdits()) return;
    view.x = event.clientX - drag.x;
    view.y = event.clientY - drag.y;
    applyTransform(view);
  });
  viewport.addEventListener('pointerup', (event) => {
    // A click (no drag) on a view marks the object's centre for the initialisation.
    if (drag && !drag.moved && !$('init-section').hidden) clickCentre(view, event);
    if (drag && drag.moved && dragEdits()) {
      dragEdit(view, event.clientX - drag.startX, event.clientY - drag.startY, event.shiftKey);
    }
    drag = null;
  });
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
    const marker = el('div', {class: 'marker', hidden: ''});
    viewport.append(img, marker);
    box.append(title, viewport);
    container.appendChild(box);
    const view = {camera: camera.name, img, viewport, label, marker, zoom: 1, x: 0, y: 0,
                  frame: -1};
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
  const query = [];
  if (state.mask) query.push('mask=1');
  if (state.candidate >= 0 && state.init && state.init.frame === frame) {
    query.push(`candidate=${state.candidate}`);
  }
  for (const view of state.views) {
    view.frame = frame;
    view.img.src = `api/frame/${frame}/view/${encodeURIComponent(view.camera)}.jpg` +
        (query.length ? '?' + query.join('&') : '');
  }
  redrawCharts();
  if (state.clickFrame !== frame) state.clicks = {};  // clicks belong to one frame
  if (!$('init-section').hidden) showClicks();
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

// --- charts (dygraphs) -------------------------------------------------------------------------

// Vertical lines across a chart's plot area at the given frames.
function drawFrameLines(canvas, area, chart, frames, style, dash) {
  canvas.save();
  canvas.strokeStyle = style;
  canvas.setLineDash(dash);
  canvas.lineWidth = 1.5;
  for (const frame of frames) {
    const x = chart.toDomXCoord(frame);
    canvas.beginPath();
    canvas.moveTo(x, area.y);
    canvas.lineTo(x, area.y + area.h);
    canvas.stroke();
  }
  canvas.restore();
}

// Bands one frame wide behind a chart at the given frames.
function drawFrameBands(canvas, area, chart, frames, style) {
  if (!frames.length) return;
  const half = Math.max(1, (chart.toDomXCoord(1) - chart.toDomXCoord(0)) / 2);
  canvas.save();
  canvas.fillStyle = style;
  for (const frame of frames) {
    canvas.fillRect(chart.toDomXCoord(frame) - half, area.y, 2 * half, area.h);
  }
  canvas.restore();
}

// A chart of per-frame series: `columns` = [{name, values}], drawn over frame numbers; a click
// shows the nearest frame, a drag zooms (double-click: all frames); `underlay(canvas, area,
// chart)` draws behind the lines; the shown frame is a black line.
function makeChart(id, columns, options, underlay) {
  const rows = [];
  for (let frame = 0; frame < state.sequence.num_frames; ++frame) {
    rows.push([frame, ...columns.map((c) => c.values[frame] ?? null)]);
  }
  if (state.charts[id]) state.charts[id].destroy();
  state.charts[id] = new Dygraph($(id), rows, Object.assign({
    labels: ['frame', ...columns.map((c) => c.name)],
    colors: columns.map((c, k) => COLORS[k % COLORS.length]),
    strokeWidth: 1.5,
    xlabel: 'frame',
    labelsDiv: $(id + '-legend') || undefined,
    labelsSeparateLines: false,
    legend: 'always',
    axes: {x: {ticker: frameTicks}},
    // The frame under the pointer (dygraphs' own x is the last hovered point, unset when the
    // pointer did not move over the chart before the click).
    clickCallback: (event) => {
      const chart = state.charts[id];
      const rect = chart.graphDiv.getBoundingClientRect();
      showFrame(chart.toDataXCoord(event.clientX - rect.left));
    },
    underlayCallback: (canvas, area, chart) => {
      if (underlay) underlay(canvas, area, chart);
      drawFrameLines(canvas, area, chart, [state.frame], '#000', []);
    },
  }, options));
}

// Ticks of a frame axis: whole frames at a round step, about one per 70 px.
function frameTicks(min, max, pixels) {
  const step = niceStep((max - min) / Math.max(1, Math.floor(pixels / 70)));
  const ticks = [];
  for (let frame = Math.ceil(min / step) * step; frame <= max; frame += step) {
    ticks.push({v: frame, label: String(frame)});
  }
  return ticks;
}

function niceStep(raw) {
  const steps = [1, 2, 5, 10, 20, 25, 50, 100, 200, 250, 500, 1000, 2000, 5000];
  return steps.find((s) => s >= raw) || 10000;
}

function redrawCharts() {
  for (const chart of Object.values(state.charts)) chart.updateOptions({});
}

// The page position (client coordinates) of `frame` on chart `id`, scrolled into view, at the
// chart's middle height: for tests and scripts.
function chartPoint(id, frame) {
  const chart = state.charts[id];
  $(id).scrollIntoView({block: 'center'});
  const rect = $(id).getBoundingClientRect();
  const area = chart.getArea();
  return [rect.left + chart.toDomXCoord(frame), rect.top + area.y + area.h / 2];
}

function drawTimeline() {
  const quality = state.quality;
  if (!quality.available) {
    $('timeline').hidden = true;
    return;
  }
  $('timeline').hidden = false;
  let max = quality.threshold_px * 1.5;
  for (const view of quality.views) {
    for (const e of view.error_px) if (e !== null) max = Math.max(max, e);
  }
  const unverifiable = [...new Set(quality.views.flatMap((view) => view.unverifiable_frames))];
  makeChart('timeline', quality.views.map((view) => ({name: view.name, values: view.error_px})),
            {ylabel: 'px', valueRange: [0, max * 1.05], connectSeparatedPoints: false,
             labelsDiv: $('legend')},
            (canvas, area, chart) => {
              drawFrameBands(canvas, area, chart, unverifiable, 'rgba(150,150,150,0.18)');
              drawFrameBands(canvas, area, chart, quality.bad_frames, 'rgba(255,50,50,0.2)');
              const y = chart.toDomYCoord(quality.threshold_px);
              canvas.save();
              canvas.strokeStyle = '#c00';
              canvas.setLineDash([6, 4]);
              canvas.beginPath();
              canvas.moveTo(area.x, y);
              canvas.lineTo(area.x + area.w, y);
              canvas.stroke();
              canvas.restore();
            });
}

// --- editing --------------------------------------------------------------------------------

// Keys of the edit buttons (in the view chosen for the buttons): a/d left/right, w/s up/down,
// r/f nearer/farther, i/k, j/l, q/e the turns about the view's x, y and viewing axes, u undo.
const EDIT_KEYS = {
  a: '[data-nudge="dx:-1"]', d: '[data-nudge="dx:1"]', w: '[data-nudge="dy:-1"]',
  s: '[data-nudge="dy:1"]', r: '[data-nudge="dz:-1"]', f: '[data-nudge="dz:1"]',
  i: '[data-nudge="rx:-1"]', k: '[data-nudge="rx:1"]', j: '[data-nudge="ry:-1"]',
  l: '[data-nudge="ry:1"]', q: '[data-nudge="rz:-1"]', e: '[data-nudge="rz:1"]', u: '#undo',
};

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
  $('reannotate').addEventListener('click', () => reannotate(
      Number($('reannotate-first').value), Number($('reannotate-last').value)));
  $('reannotate-here').addEventListener('click',
      () => reannotate(state.frame, state.sequence.num_frames - 1));
  $('refine').addEventListener('click', () => {
    $('edit-status').textContent = `Refining frame ${state.frame} …`;
    edit(() => post(`api/frame/${state.frame}/refine`));
  });
  $('keyframe').addEventListener('click', async () => {
    try {
      const written = await post(`api/frame/${state.frame}/keyframe`);
      document.body.dataset.keyframe = String(written.frame);
      $('reannotate-first').value = String(written.first);
      $('reannotate-last').value = String(written.last);
      $('edit-status').textContent = `Keyframe ${written.frame} written to ${written.path}. ` +
          `Re-annotate frames ${written.first}–${written.last} around it below (or run: ` +
          `${written.command}).`;
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

// --- jobs: re-annotation and initialisation in the background --------------------------------

// Starts a job with POST `url`, shows its progress until it ends, then calls `finished(job)`.
async function runJob(url, finished) {
  const section = $('job-section');
  section.hidden = false;
  try {
    await post(url);
  } catch (error) {
    $('job-status').textContent = String(error.message);
    document.body.dataset.job = 'failed';
    return;
  }
  document.body.dataset.job = 'running';
  for (;;) {
    const job = await getJson('api/job');
    $('job-progress').max = Math.max(1, job.total);
    $('job-progress').value = job.done;
    $('job-status').textContent = job.state === 'running' ?
        `${job.name}: ${job.done} / ${job.total}` : `${job.name}: ${job.message}`;
    if (job.state !== 'running') {
      if (job.state === 'done') await finished(job);
      document.body.dataset.job = job.state;
      return;
    }
    await new Promise((resolve) => setTimeout(resolve, 300));
  }
}

// Re-annotates frames first..last from the keyframes, then shows the new annotation.
function reannotate(first, last) {
  runJob(`api/reannotate?first=${first}&last=${last}`, async () => {
    [state.quality, state.trajectory] =
        await Promise.all([getJson('api/quality'), getJson('api/trajectory')]);
    describeQuality();
    drawTimeline();
    drawTrajectory();
    showFrame(state.frame);
  });
}

// Initialisation: a click on a view marks the object's centre there (image pixels).
function clickCentre(view, event) {
  const rect = view.img.getBoundingClientRect();
  if (!view.img.naturalWidth || !rect.width) return;
  const x = (event.clientX - rect.left) / rect.width * view.img.naturalWidth;
  const y = (event.clientY - rect.top) / rect.height * view.img.naturalHeight;
  if (state.clickFrame !== state.frame) state.clicks = {};
  state.clickFrame = state.frame;
  state.clicks[view.camera] = [x, y];
  showClicks();
}

function placeMarker(view) {
  const click = state.clicks[view.camera];
  view.marker.hidden = !click;
  if (!click || !view.img.naturalWidth) return;
  const scale = view.img.clientWidth / view.img.naturalWidth * view.zoom;
  view.marker.style.left = `${view.x + click[0] * scale}px`;
  view.marker.style.top = `${view.y + click[1] * scale}px`;
}

function showClicks() {
  const entries = Object.entries(state.clicks);
  $('init-frame').textContent = String(state.frame);
  $('init-clicks').textContent = entries.length ?
      entries.map(([camera, [x, y]]) => `${camera}: ${x.toFixed(1)}, ${y.toFixed(1)}`).join('; ') :
      'no clicks yet';
  $('init-find').disabled = entries.length === 0;
  for (const view of state.views) placeMarker(view);
}

function findInitialPose() {
  const clicks = Object.entries(state.clicks).map(([camera, [x, y]]) =>
    `click=${encodeURIComponent(`${camera}:${x.toFixed(2)},${y.toFixed(2)}`)}`);
  $('init-status').textContent = `Searching the pose of frame ${state.frame} …`;
  runJob(`api/init?frame=${state.frame}&${clicks.join('&')}`, async (job) => {
    state.init = await getJson('api/init');
    $('init-status').textContent = job.message;
    const list = $('init-candidates');
    list.replaceChildren('candidates (magenta contour):');
    state.init.candidates.forEach((candidate, k) => {
      const label = el('label', {});
      const radio = el('input', {type: 'radio', name: 'candidate', value: String(k),
                                 'data-candidate': String(k)});
      radio.addEventListener('change', () => chooseCandidate(k));
      label.append(radio, ` ${k + 1}: energy ${candidate.energy.toFixed(4)}`);
      list.appendChild(label);
    });
    document.body.dataset.initCandidates = String(state.init.candidates.length);
    list.querySelector('input').checked = true;
    chooseCandidate(0);
  });
}

function chooseCandidate(k) {
  state.candidate = k;
  $('init-save').disabled = false;
  showFrame(state.init.frame);
}

async function saveInitialPose() {
  try {
    const saved = await post(`api/init/save?candidate=${state.candidate}` +
                             ($('init-overwrite').checked ? '&overwrite=1' : ''));
    document.body.dataset.initSaved = saved.path;
    $('init-status').textContent = `Frame ${saved.frame}'s pose written to ${saved.path}. ` +
        (state.sequence.annotation_target ? 'Annotate the sequence below, or run: ' :
                                            'Annotate with: ') + saved.command;
  } catch (error) {
    $('init-status').textContent = String(error.message);
  }
}

// Annotates the whole sequence into bcot review's --annotation directory, then reloads the page,
// which is then the page of that annotation.
function annotateSequence() {
  runJob('api/annotate', () => window.location.reload());
}

function bindInitialisation() {
  $('init-section').hidden = false;
  const target = state.sequence.annotation_target;
  $('annotate-row').hidden = !target;
  if (target) {
    $('annotate-target').textContent = target;
    $('annotate').addEventListener('click', annotateSequence);
  }
  $('init-clear').addEventListener('click', () => {
    state.clicks = {};
    showClicks();
  });
  $('init-find').addEventListener('click', findInitialPose);
  $('init-save').addEventListener('click', saveInitialPose);
  showClicks();
}

// --- trajectory -------------------------------------------------------------------------------

function drawTrajectory() {
  const trajectory = state.trajectory;
  $('trajectory-section').hidden = !trajectory.available;
  if (!trajectory.available) return;
  const centre = trajectory.centre_mm;
  const relative = (values) => values.map((v) => v - values[0]);
  const keyframes = (canvas, area, chart) =>
    drawFrameLines(canvas, area, chart, trajectory.keyframes, '#a40', [4, 3]);
  makeChart('rotation', [{name: 'rotation (deg)', values: trajectory.rotation_deg}],
            {ylabel: 'deg'}, keyframes);
  makeChart('translation', [{name: 'x (mm)', values: relative(centre.x)},
                            {name: 'y (mm)', values: relative(centre.y)},
                            {name: 'z (mm)', values: relative(centre.z)}],
            {ylabel: 'mm'}, keyframes);
  const list = trajectory.keyframes.length ?
      `keyframes (dashed): ${trajectory.keyframes.join(', ')}` : 'no keyframes';
  $('trajectory-note').textContent = 'Rotation from frame 0 (deg) and the object centre\'s ' +
      `displacement from frame 0 along the rig axes (mm); ${list}. Click to jump to a frame, ` +
      'drag to zoom, double-click for all frames.';
}

function describeQuality() {
  const quality = state.quality;
  const note = $('timeline-note');
  if (!quality.available) {
    note.textContent = state.sequence.annotation ?
        'No quality.json in the annotation: no error timeline.' :
        'No annotation: no error timeline.';
    $('bad-frames').textContent = 'unknown (no quality.json)';
    return;
  }
  note.textContent = `The ${quality.statistic} reprojection error (px) per view; dashed: the ` +
      `rejection threshold ${quality.threshold_px} px; red bands: bad frames; grey: cannot ` +
      'be told. Click to jump to a frame, drag to zoom, double-click for all frames. Bad ' +
      'frames per view: ' +
      quality.views.map((view) => `${view.name} ${view.bad_frames.length}`).join(', ') + '.';
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
  document.addEventListener('keydown', (event) => {
    if (event.target.tagName === 'INPUT' && event.key !== ' ') return;
    if (event.target.tagName === 'SELECT') return;
    const moves = {ArrowLeft: -1, ArrowRight: 1, PageUp: -10, PageDown: 10};
    const editButton = !$('edit-section').hidden && !event.ctrlKey && !event.altKey &&
        !event.metaKey && EDIT_KEYS[event.key.toLowerCase()];
    if (editButton) {
      document.querySelector(editButton).click();
    } else if (event.key in moves) {
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
  $('mask').addEventListener('change', (event) => {
    state.mask = event.target.checked;
    showFrame(state.frame);
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
  if (!sequence.contour) bindInitialisation();
  showFrame(frameFromAddress());
  document.body.dataset.ready = 'yes';
}

start();
