// twinray view: the page. It follows the server's state (server-sent events), shows the
// renders of the latest state, and asks the server for explanations, views and timings.
'use strict';

const $ = (id) => document.getElementById(id);
const page = {
  state: null,
  shown: 0,            // id of the render whose images are drawn
  images: null,        // {width, height, a, b, heat, abs: canvases; dataA, dataB: ImageData}
  mode: 'side',
  flipB: false,
  wipe: 0.5,
  exposure: 4,
  zoom: 1,             // times the fitted scale
  center: [0.5, 0.5],  // image point at the canvas centre, as fractions of its size
  camera: null,        // {eye, target} the page asked for last
  explained: null,     // {render, x, y}
};

// ---- the server's state -------------------------------------------------------------------

const events = new EventSource('/events');
events.addEventListener('state', (e) => apply(JSON.parse(e.data), performance.now()));
events.onerror = () => setStatus('disconnected: is twinray view still running?', true);

function setStatus(text, busy) {
  $('status').textContent = text;
  $('status').classList.toggle('busy', busy);
}

function apply(state, received) {
  const before = page.state;
  page.state = state;
  $('scene').textContent = state.scene.name;
  $('sets').textContent = `A = ${state.sets[0]}  ·  B = ${state.sets[1]}`;
  setStatus(state.status, state.status !== 'idle');
  $('problem').hidden = !state.problem;
  if (state.problem) {
    $('problem-title').textContent = `The ${state.problem.what} failed`;
    $('problem-text').textContent = state.problem.text;
  }
  $('watched').replaceChildren(...state.live.map((w) => el('li', w)));
  controls(state, before);
  showTiming(state.timing);
  if (state.render && state.render.id !== page.shown) {
    loadRender(state.render, received);
  }
}

// The frame slider for moving scenes; the camera for still ones.
function controls(state, before) {
  const moving = state.scene.frames > 1;
  $('frame-control').hidden = !moving;
  $('camera-control').hidden = moving;
  $('frame').max = String(state.scene.frames - 1);
  if (!before || before.scene.name !== state.scene.name || !page.camera) {
    page.camera = { eye: state.scene.eye.slice(), target: state.scene.target.slice() };
  }
  $('frame-value').textContent = `${state.wanted.frame} of ${state.scene.frames}`;
}

function loadRender(render, received) {
  const load = (name) => new Promise((resolve, reject) => {
    const img = new Image();
    img.onload = () => resolve(img);
    img.onerror = () => reject(new Error(`render ${render.id}: ${name} did not load`));
    img.src = `/render/${render.id}/${name}`;
  });
  Promise.all(['a.png', 'b.png', 'diff.png'].map(load)).then(([a, b, heat]) => {
    if (page.state.render && page.state.render.id > render.id) return; // a newer one is loading
    page.images = prepare(a, b, heat);
    page.shown = render.id;
    showFigures(render);
    draw();
    const delivered = performance.now() - received;
    const latency = render.save_to_ready_ms === null ? null : render.save_to_ready_ms + delivered;
    showLatency(render, latency);
    document.body.dataset.shown = String(render.id);
    document.body.dataset.preview = String(render.preview);
    if (latency !== null) document.body.dataset.saveToPageMs = latency.toFixed(0);
  }).catch((e) => setStatus(e.message, true));
}

function canvasOf(img) {
  const c = document.createElement('canvas');
  c.width = img.naturalWidth;
  c.height = img.naturalHeight;
  c.getContext('2d').drawImage(img, 0, 0);
  return c;
}

function prepare(a, b, heat) {
  const [ca, cb, ch] = [canvasOf(a), canvasOf(b), canvasOf(heat)];
  const data = (c) => c.getContext('2d').getImageData(0, 0, c.width, c.height);
  const images = { width: ca.width, height: ca.height, a: ca, b: cb, heat: ch, dataA: data(ca), dataB: data(cb) };
  images.abs = absolute(images);
  return images;
}

// |A - B| per channel, scaled by 2^exposure, in 8-bit steps.
function absolute(images) {
  const c = document.createElement('canvas');
  c.width = images.width;
  c.height = images.height;
  const ctx = c.getContext('2d');
  const out = ctx.createImageData(c.width, c.height);
  const [a, b] = [images.dataA.data, images.dataB.data];
  const gain = Math.pow(2, page.exposure);
  for (let i = 0; i < a.length; i += 4) {
    for (let k = 0; k < 3; k++) out.data[i + k] = Math.min(255, Math.abs(a[i + k] - b[i + k]) * gain);
    out.data[i + 3] = 255;
  }
  ctx.putImageData(out, 0, 0);
  return c;
}

// ---- figures ------------------------------------------------------------------------------

function el(tag, text, cls) {
  const e = document.createElement(tag);
  if (text !== undefined) e.textContent = text;
  if (cls) e.className = cls;
  return e;
}

function row(name, ...cells) {
  const tr = el('tr');
  tr.append(el('th', name), ...cells.map((c) => el('td', c, 'n')));
  return tr;
}

const fmt = (v, digits) => (v === null || v === undefined ? 'n/a' : Number(v).toFixed(digits));

function showFigures(render) {
  const r = render.report;
  $('verdict').textContent = r.pass ? 'PASS' : 'FAIL';
  $('verdict').className = r.pass ? 'pass' : 'fail';
  const shot = render.shot;
  const size = `${shot.width}x${shot.height}${render.preview ? ' (preview; full size follows)' : ''}`;
  $('render-words').textContent = `render ${render.id}: ${size}, frame ${shot.frame}, on ${r.device}`;
  const w = (s) => `${s.unwritten} / ${s.non_finite}`;
  $('numbers').replaceChildren(
    row('', 'A', 'B'),
    row('RMSE', fmt(r.rmse, 6)),
    row('PSNR dB', r.psnr === null ? 'identical' : fmt(r.psnr, 1)),
    row('largest step', String(r.max_abs_diff)),
    row(`pixels over ${r.pixel_threshold} steps`, String(r.pixels_over_threshold)),
    row('hit mismatches (off silhouette)', `${r.hit_mismatches} (${r.hit_mismatches_off_silhouette})`),
    row('unwritten / non-finite', w(r.written_a), w(r.written_b)),
    row('GPU ms, one cold trace', fmt(r.gpu_ms_a, 3), fmt(r.gpu_ms_b, 3)),
  );
  $('failures').replaceChildren(...r.failures.map((f) => el('li', f)));
  $('named').replaceChildren(...r.pixels.map((p) => {
    const what = p.hit_mismatch ? 'hit mismatch' : `${p.steps} steps`;
    const li = el('li', `${p.x},${p.y}: ${what}`);
    li.onclick = () => explain(render.id, p.x, p.y);
    return li;
  }));
  if (r.pixels.length === 0) $('named').append(el('li', 'none over the threshold'));
}

function showLatency(render, latency) {
  if (latency === null) {
    $('latency').textContent = '';
    return;
  }
  const parts = [];
  if (render.build_ms !== null) parts.push(`build ${(render.build_ms / 1000).toFixed(1)} s`);
  parts.push(`render ${(render.render_ms / 1000).toFixed(1)} s`);
  const size = `${render.shot.width}x${render.shot.height}${render.preview ? ' preview' : ''}`;
  $('latency').textContent = `save → page ${(latency / 1000).toFixed(1)} s at ${size} (${parts.join(', ')})`;
}

function showTiming(timing) {
  const box = $('timing');
  $('measure').disabled = timing.running;
  if (timing.running) {
    box.textContent = 'timing A against B and A against itself (10 traces x 6 placements each)...';
  } else if (timing.error) {
    box.textContent = `timing failed: ${timing.error}`;
  } else if (timing.ab) {
    const words = (r) => (r.timing ? r.timing.verdict : 'no timestamps on this device');
    box.replaceChildren(
      el('div', `A against B: ${words(timing.ab)}`),
      el('div', `null control (A against itself): ${words(timing.null)}`),
      el('div', `of render ${timing.render}, at ${timing.ab.width}x${timing.ab.height}`, 'mono'),
    );
  } else {
    box.textContent = 'The figures above are one cold trace each: a ratio needs an interval.';
  }
}

$('measure').onclick = () => post('/api/timing', '');

// ---- drawing ------------------------------------------------------------------------------

// Screen transform of a canvas: scale (screen pixels per image pixel) and offset.
function transform(canvas) {
  const im = page.images;
  const fit = Math.min(canvas.width / im.width, canvas.height / im.height);
  const scale = fit * page.zoom;
  const ox = canvas.width / 2 - page.center[0] * im.width * scale;
  const oy = canvas.height / 2 - page.center[1] * im.height * scale;
  return { scale, ox, oy };
}

function sourceFor(which) {
  const im = page.images;
  switch (page.mode) {
    case 'side': return which === 'a' ? im.a : im.b;
    case 'flip': return page.flipB ? im.b : im.a;
    case 'heat': return im.heat;
    case 'abs': return im.abs;
    default: return im.a;
  }
}

function paint(canvas, source, clip) {
  canvas.width = canvas.clientWidth;
  canvas.height = canvas.clientHeight;
  const ctx = canvas.getContext('2d');
  ctx.imageSmoothingEnabled = false;
  ctx.fillStyle = '#111';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  const t = transform(canvas);
  ctx.save();
  if (clip) {
    ctx.beginPath();
    ctx.rect(clip[0], 0, clip[1] - clip[0], canvas.height);
    ctx.clip();
  }
  ctx.setTransform(t.scale, 0, 0, t.scale, t.ox, t.oy);
  ctx.drawImage(source, 0, 0);
  ctx.restore();
}

function draw() {
  const labels = { side: ['A', 'B'], wipe: ['A | B', ''], flip: [page.flipB ? 'B' : 'A', ''], heat: ['difference (diff.png)', ''], abs: [`|A − B| × 2^${page.exposure}`, ''] };
  $('panel-b').hidden = page.mode !== 'side';
  $('wipe-control').hidden = page.mode !== 'wipe';
  $('exposure-control').hidden = page.mode !== 'abs';
  [$('label-a').textContent, $('label-b').textContent] = labels[page.mode];
  $('zoom-value').textContent = `zoom ${page.zoom.toFixed(page.zoom < 10 ? 2 : 0)}x`;
  document.body.dataset.mode = page.mode;
  if (!page.images) return;
  const ca = $('canvas-a');
  if (page.mode === 'wipe') {
    paint(ca, page.images.a);
    const x = Math.round(ca.width * page.wipe);
    const ctx = ca.getContext('2d');
    paintOver(ca, page.images.b, x);
    ctx.fillStyle = '#e9a33a';
    ctx.fillRect(x - 1, 0, 2, ca.height);
  } else {
    paint(ca, sourceFor('a'));
  }
  if (page.mode === 'side') paint($('canvas-b'), sourceFor('b'));
}

// Draws `source` over the canvas right of screen column `x` (the wipe's B side).
function paintOver(canvas, source, x) {
  const ctx = canvas.getContext('2d');
  const t = transform(canvas);
  ctx.save();
  ctx.beginPath();
  ctx.rect(x, 0, canvas.width - x, canvas.height);
  ctx.clip();
  ctx.imageSmoothingEnabled = false;
  ctx.setTransform(t.scale, 0, 0, t.scale, t.ox, t.oy);
  ctx.drawImage(source, 0, 0);
  ctx.restore();
}

window.addEventListener('resize', draw);

for (const button of document.querySelectorAll('#modes button')) {
  button.onclick = () => {
    if (button.dataset.mode === 'flip' && page.mode === 'flip') page.flipB = !page.flipB;
    page.mode = button.dataset.mode;
    for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('on', b === button);
    draw();
  };
}
$('wipe').oninput = () => { page.wipe = Number($('wipe').value); draw(); };
$('exposure').oninput = () => {
  page.exposure = Number($('exposure').value);
  $('exposure-value').textContent = `2^${page.exposure}`;
  if (page.images) page.images.abs = absolute(page.images);
  draw();
};
$('fit').onclick = () => { page.zoom = 1; page.center = [0.5, 0.5]; draw(); };
document.addEventListener('keydown', (e) => {
  if (e.key === 'f' || e.key === 'F') {
    page.flipB = page.mode === 'flip' ? !page.flipB : false;
    page.mode = 'flip';
    for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('on', b.dataset.mode === 'flip');
    draw();
  }
});

// ---- mouse: zoom, pan, click to explain; or the camera ------------------------------------

// The image pixel under a mouse event on `canvas`, or null outside the image.
function pixelAt(canvas, e) {
  if (!page.images) return null;
  const rect = canvas.getBoundingClientRect();
  const t = transform(canvas);
  const x = Math.floor((e.clientX - rect.left - t.ox) / t.scale);
  const y = Math.floor((e.clientY - rect.top - t.oy) / t.scale);
  if (x < 0 || y < 0 || x >= page.images.width || y >= page.images.height) return null;
  return [x, y];
}

const cameraMode = () => $('mouse').value === 'camera' && page.state && page.state.scene.frames === 1;

for (const canvas of [$('canvas-a'), $('canvas-b')]) {
  let drag = null;
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    if (cameraMode()) return dolly(Math.exp(e.deltaY * 0.001));
    if (!page.images) return;
    const rect = canvas.getBoundingClientRect();
    const before = transform(canvas);
    const px = (e.clientX - rect.left - before.ox) / before.scale;
    const py = (e.clientY - rect.top - before.oy) / before.scale;
    page.zoom = Math.min(512, Math.max(0.25, page.zoom * Math.exp(-e.deltaY * 0.002)));
    // Keep the image point under the mouse where it was.
    const scale = transform(canvas).scale;
    page.center = [
      (px - (e.clientX - rect.left - canvas.width / 2) / scale) / page.images.width,
      (py - (e.clientY - rect.top - canvas.height / 2) / scale) / page.images.height,
    ];
    draw();
  }, { passive: false });
  canvas.addEventListener('mousedown', (e) => { drag = { x: e.clientX, y: e.clientY, moved: 0, shift: e.shiftKey }; });
  canvas.addEventListener('mousemove', (e) => {
    readout(canvas, e);
    if (!drag) return;
    const [dx, dy] = [e.clientX - drag.x, e.clientY - drag.y];
    drag.moved += Math.abs(dx) + Math.abs(dy);
    [drag.x, drag.y] = [e.clientX, e.clientY];
    if (cameraMode()) {
      if (drag.shift) panCamera(dx, dy); else orbit(dx, dy);
    } else if (page.images) {
      const t = transform(canvas);
      page.center[0] -= dx / (t.scale * page.images.width);
      page.center[1] -= dy / (t.scale * page.images.height);
      draw();
    }
  });
  canvas.addEventListener('mouseup', (e) => {
    const click = drag && drag.moved < 4;
    drag = null;
    if (cameraMode()) return sendCamera(true);
    if (!click) return;
    const p = pixelAt(canvas, e);
    if (p) explain(page.shown, p[0], p[1]);
  });
  canvas.addEventListener('mouseleave', () => { drag = null; $('readout').textContent = ''; });
}

function readout(canvas, e) {
  const p = pixelAt(canvas, e);
  if (!p) { $('readout').textContent = ''; return; }
  const i = (p[1] * page.images.width + p[0]) * 4;
  const rgb = (d) => `${d[i]} ${d[i + 1]} ${d[i + 2]}`;
  $('readout').textContent = `${p[0]},${p[1]}  A ${rgb(page.images.dataA.data)}  B ${rgb(page.images.dataB.data)}`;
}

// ---- the camera (still scenes) -------------------------------------------------------------

const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const mul = (a, s) => a.map((v) => v * s);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a) => mul(a, 1 / Math.hypot(...a));

// Rotates `v` about unit axis `k` by `angle` (Rodrigues).
function rotate(v, k, angle) {
  const [c, s] = [Math.cos(angle), Math.sin(angle)];
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

function orbit(dx, dy) {
  const up = unit(page.state.scene.up);
  let offset = sub(page.camera.eye, page.camera.target);
  offset = rotate(offset, up, -dx * 0.01);
  const right = unit(cross(up, offset));
  const turned = rotate(offset, right, -dy * 0.01);
  // Stop short of the poles, where up and the view direction meet.
  if (Math.abs(dot(unit(turned), up)) < 0.995) offset = turned;
  page.camera.eye = add(page.camera.target, offset);
  sendCamera(false);
}

function panCamera(dx, dy) {
  const up = unit(page.state.scene.up);
  const offset = sub(page.camera.eye, page.camera.target);
  const right = unit(cross(up, offset));
  const trueUp = unit(cross(offset, right));
  const step = Math.hypot(...offset) * 0.002;
  const move = add(mul(right, -dx * step), mul(trueUp, dy * step));
  page.camera.eye = add(page.camera.eye, move);
  page.camera.target = add(page.camera.target, move);
  sendCamera(false);
}

function dolly(factor) {
  const offset = sub(page.camera.eye, page.camera.target);
  page.camera.eye = add(page.camera.target, mul(offset, factor));
  sendCamera(true);
}

let cameraTimer = null;
// Sends the camera now (`final`) or at most every quarter second while dragging.
function sendCamera(final) {
  if (cameraTimer && !final) return;
  clearTimeout(cameraTimer);
  cameraTimer = setTimeout(() => { cameraTimer = null; }, 250);
  post('/api/view', JSON.stringify({ frame: 0, eye: page.camera.eye, look_at: page.camera.target }));
}

$('camera-reset').onclick = () => {
  page.camera = { eye: page.state.scene.eye.slice(), target: page.state.scene.target.slice() };
  post('/api/view', JSON.stringify({ frame: 0 }));
};
$('frame').oninput = () => {
  $('frame-value').textContent = `${$('frame').value} of ${page.state.scene.frames}`;
};
$('frame').onchange = () => post('/api/view', JSON.stringify({ frame: Number($('frame').value) }));

function post(url, body) {
  return fetch(url, { method: 'POST', body, headers: { 'Content-Type': 'application/json' } }).then(async (r) => {
    if (!r.ok) setStatus(`${url}: ${await r.text()}`, true);
  });
}

// ---- explain --------------------------------------------------------------------------------

function explain(render, x, y) {
  page.explained = { render, x, y };
  const body = $('explain-body');
  body.replaceChildren(el('p', `explaining pixel ${x},${y} of render ${render}...`));
  fetch(`/api/explain?render=${render}&x=${x}&y=${y}`).then(async (r) => {
    if (page.explained.x !== x || page.explained.y !== y) return; // another click since
    if (!r.ok) {
      body.replaceChildren(el('p', `pixel ${x},${y}: the explain failed`), el('pre', await r.text()));
      return;
    }
    showExplain(await r.json());
  }).catch((e) => body.replaceChildren(el('p', `pixel ${x},${y}: ${e.message}`)));
}

const vec = (v, digits = 4) => (v ? `(${v.map((x) => Number(x).toFixed(digits)).join(', ')})` : '-');

function showExplain(report) {
  const body = $('explain-body');
  const parting = report.parting;
  const head = el('div', '', 'parting');
  head.append(el('strong', `pixel ${report.pixel[0]},${report.pixel[1]}${report.frame ? ` of frame ${report.frame}` : ''}: `));
  head.append(el('span', parting.text));
  if (parting.stage) head.append(el('div', `stage: ${parting.stage}`));
  const pixels = el('table');
  pixels.append(row('set', 'image', 'rays add up to'));
  for (const p of report.sets) pixels.append(row(p.set, vec(p.image), vec(p.rays)));
  body.replaceChildren(head, pixels, ...report.specs.map((s) => el('div', s, 'mono')));
  for (const sample of report.samples) body.append(sampleDetails(sample, parting));
}

function sampleDetails(sample, parting) {
  const details = el('details');
  const parted = parting.sample === sample.index;
  details.open = parted;
  if (parted) details.className = 'parted';
  details.append(el('summary', `sample ${sample.index}, stratum ${sample.stratum.join(',')}: reference ${sample.reference.verdict}`));
  details.append(el('div', `ray from ${vec(sample.origin)} along ${vec(sample.direction)}`, 'mono'));
  const rays = el('table');
  rays.append(row('', 'outcome', 'object', 't', 'normal', 'colour'));
  const ref = sample.reference;
  rays.append(row('reference', ref.verdict, ref.object ?? '-', ref.t === null ? '-' : fmt(ref.t, 6), vec(ref.normal), ''));
  for (const s of sample.sets) {
    rays.append(row(s.set, s.outcome, s.object ?? '-', s.t === null ? '-' : fmt(s.t, 6), vec(s.geometric_normal), vec(s.color, 3)));
  }
  details.append(rays);
  for (const s of sample.sets) {
    if (s.lights.length === 0) continue;
    const lights = el('table');
    lights.append(row(`${s.set}'s shadow rays`, 'light', 'cell', 'occluded', 'reference'));
    s.lights.forEach((l, k) => {
      const mark = parted && parting.light_sample === k ? ' ◀' : '';
      const occluded = l.traced ? String(l.occluded) : 'not traced';
      lights.append(row(`#${k}${mark}`, String(l.light), l.cell.join(','), occluded, l.reference ?? '-'));
    });
    details.append(lights);
  }
  return details;
}
