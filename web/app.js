// phongcl serve's page: holds the scene JSON, sends whole scenes on edits (one request in flight,
// the newest edit after it), and shows frames from a long poll of /api/frame. Plain JS, no build.
'use strict';

const $ = (id) => document.getElementById(id);

const state = {
  scene: null,          // the scene document, as the server holds it (plus lights disabled here)
  disabled: new Set(),  // lights switched off: kept in the page, left out of what is sent
  sceneVersion: 0,      // the server's version of the scene we hold
  frameVersion: 0,      // the newest frame shown
  lightGroups: '',      // the scene's light groups the controls show, one name a line
  receivedVersion: 0,   // the newest frame received (the next poll asks for a newer one)
  receivedCount: 0, shownSequence: 0,  // frames in order of arrival: a slow decode never overwrites a newer one
  shown: null,          // the ImageBitmap on screen
  hasBeauty: false, beauty: null, beautyQuery: '',  // the renderer's own image, for the split
  selectedLight: 0,
  selectedMaterial: -1,
  sending: false, dirty: false,
  picking: false,       // a /api/pick under the cursor in flight (its edit follows)
  imageSize: [0, 0],
};

// Input-event-to-image-displayed figures, read by scripts/checks/70-browser.sh.
const metrics = { edits: [], latencies: [], displayed: [] };
window.phongclMetrics = metrics;
window.phongclState = state;

function setStatus(text, isError) {
  const status = $('status');
  status.textContent = text;
  status.className = isError ? 'error' : '';
}

async function errorOf(response) {
  try { return (await response.json()).error || response.statusText; } catch { return response.statusText; }
}

// ---- Scene: what is sent, and when ----

function sceneToSend() {
  const scene = structuredClone(state.scene);
  scene.lights = (scene.lights || []).filter((_, i) => !state.disabled.has(i));
  return scene;
}

function edited() {
  metrics.edits.push({ time: performance.now(), version: null });
  state.dirty = true;
  if (!state.sending) sendScene();
}

async function sendScene() {
  state.sending = true;
  while (state.dirty) {
    state.dirty = false;
    const waiting = metrics.edits.filter((e) => e.version === null);
    const response = await fetch('api/scene', {
      method: 'PUT', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(sceneToSend()),
    });
    if (response.ok) {
      state.sceneVersion = (await response.json()).scene_version;
      waiting.forEach((e) => { e.version = state.sceneVersion; });
      setStatus('', false);
    } else {
      waiting.forEach((e) => { e.version = -1; });
      setStatus(await errorOf(response), true);
    }
  }
  state.sending = false;
}

async function loadScene() {
  const response = await fetch('api/scene');
  state.scene = await response.json();
  state.sceneVersion = Number(response.headers.get('X-Scene-Version'));
  state.disabled.clear();
  renderLights();
  renderMaterials();
}

// ---- Frames: long poll, newest only ----

// With "stream at display size" the server scales the frame to the pixels the page shows it at:
// at 1080p in a smaller window that is a fraction of the encoding and decoding.
function streamWidth() {
  const [width] = state.imageSize;
  const shown = Math.ceil($('stage').clientWidth * window.devicePixelRatio);
  return $('fit').checked && width > 0 ? `&width=${Math.max(1, Math.min(width, shown))}` : '';
}

function viewQuery() {
  return `format=${$('format').value}&${colorManagement.query()}&aov=${$('aov').value}${streamWidth()}`;
}

let pollAbort = null;

// The poll for the next frame goes out as soon as a frame's bytes are in, so the server shades and
// encodes the next one while this one decodes (off the main thread: createImageBitmap) and draws.
async function pollFrames() {
  for (;;) {
    pollAbort = new AbortController();
    const asked = performance.now();
    let response;
    try {
      response = await fetch(`api/frame?after=${state.receivedVersion}&timeout_ms=20000&${viewQuery()}`,
                             { signal: pollAbort.signal });
      if (response.status === 204) continue;
      if (!response.ok) {
        setStatus(await errorOf(response), true);
        state.receivedVersion = Number(response.headers.get('X-Frame-Version')) || state.receivedVersion;
        // 503: the server holds as many waiting requests as it allows (other tabs); ask again later.
        const retry = Number(response.headers.get('Retry-After'));
        if (response.status === 503) await new Promise((r) => setTimeout(r, 1000 * (retry > 0 ? retry : 1)));
        continue;
      }
      const headed = performance.now();
      const blob = await response.blob();
      state.receivedVersion = Number(response.headers.get('X-Frame-Version'));
      showFrame(blob, response, ++state.receivedCount, { asked, headed, received: performance.now() });
    } catch (error) {
      if (error.name !== 'AbortError') await new Promise((r) => setTimeout(r, 1000));
    }
  }
}

async function showFrame(blob, response, sequence, times) {
  let bitmap;
  try { bitmap = await createImageBitmap(blob); } catch { return; /* not an image: a newer frame follows */ }
  if (sequence <= state.shownSequence) { bitmap.close(); return; }  // a later frame decoded first
  state.shownSequence = sequence;
  if (state.shown) state.shown.close();
  state.shown = bitmap;
  drawView();
  const now = performance.now();
  const frameVersion = Number(response.headers.get('X-Frame-Version'));
  const sceneVersion = Number(response.headers.get('X-Scene-Version'));
  state.frameVersion = frameVersion;
  metrics.displayed.push({ time: now, frameVersion, sceneVersion, wait_ms: times.headed - times.asked,
                           transfer_ms: times.received - times.headed, decode_ms: now - times.received });
  for (const e of metrics.edits) {
    if (e.version !== null && e.version > 0 && e.version <= sceneVersion && e.shown === undefined) {
      e.shown = now;
      metrics.latencies.push(now - e.time);
    }
  }
  showTimings(response);
  // Another tab changed the scene: take its version unless an edit of ours is on its way.
  if (sceneVersion > state.sceneVersion && !state.sending && !state.dirty) loadScene();
}

// The relit frame, and right of the split the renderer's own image at the same size.
function drawView() {
  const view = $('view'), frame = state.shown;
  if (!frame) return;
  if (view.width !== frame.width || view.height !== frame.height) {
    view.width = frame.width;
    view.height = frame.height;
  }
  const context = view.getContext('2d');
  context.drawImage(frame, 0, 0);
  const split = Number($('split').value) / 100;
  if (state.beauty && split < 1) {
    const x = Math.round(split * view.width);
    context.drawImage(state.beauty, (x / view.width) * state.beauty.width, 0,
                      ((view.width - x) / view.width) * state.beauty.width, state.beauty.height,
                      x, 0, view.width - x, view.height);
    context.fillStyle = '#e8a33d';
    context.fillRect(x, 0, 1, view.height);
  }
}

// The beauty pass with the view's display settings, fetched again when they change.
async function loadBeauty() {
  if (!state.hasBeauty) return;
  const query = `format=png&${colorManagement.query()}${streamWidth()}`;
  if (query === state.beautyQuery) return;
  state.beautyQuery = query;
  const response = await fetch(`api/beauty?${query}`);
  if (!response.ok) return setStatus(await errorOf(response), true);
  const bitmap = await createImageBitmap(await response.blob());
  if (query !== state.beautyQuery) { bitmap.close(); return; }
  if (state.beauty) state.beauty.close();
  state.beauty = bitmap;
  drawView();
}

// View changes re-encode the newest frame: ask for anything newer than the one before it.
function viewChanged() {
  state.receivedVersion = Math.max(0, state.frameVersion - 1);
  if (pollAbort) pollAbort.abort();
  loadBeauty();
}

// ---- Timings and kernel ----

const clientFrames = [];
function showTimings(response) {
  const now = performance.now();
  clientFrames.push(now);
  while (clientFrames.length && clientFrames[0] < now - 2000) clientFrames.shift();
  const recent = metrics.latencies.slice(-20).sort((a, b) => a - b);
  const rows = [
    ['shade (server)', response.headers.get('X-Shade-Ms'), 'ms'],
    ['kernel', response.headers.get('X-Kernel-Ms'), 'ms'],
    ['encode', response.headers.get('X-Encode-Ms'), 'ms'],
    ['transfer (page)', metrics.displayed.at(-1).transfer_ms, 'ms'],
    ['decode and draw (page)', metrics.displayed.at(-1).decode_ms, 'ms'],
    ['frames shown', (clientFrames.length / 2).toFixed(1), 'fps'],
    ['input to image (median of 20)', recent.length ? recent[recent.length >> 1].toFixed(0) : '-', 'ms'],
  ];
  $('timings').tBodies[0].innerHTML = rows
    .map(([name, value, unit]) => `<tr><td>${name}</td><td>${value === null ? '-' : Number(value).toFixed(1).replace(/\.0$/, '')} ${unit}</td></tr>`)
    .join('');
}

async function refreshKernel() {
  const stats = await (await fetch('api/stats')).json();
  if (stats.frame) {
    $('kernel').textContent = `${stats.frame.kernel} · build ${stats.frame.build} · ${stats.width}×${stats.height} · ${stats.device}`;
    if (stats.frame.error) setStatus(stats.frame.error, true);
  }
  state.imageSize = [stats.width, stats.height];  // the G-buffer's pixels, whatever size is streamed
  if (stats.beauty !== state.hasBeauty) {
    state.hasBeauty = stats.beauty;
    $('split-row').hidden = !stats.beauty;
    loadBeauty();
  }
  $('precision').value = stats.settings.precision;
  $('shadows').value = stats.settings.shadows;
  showLightGroups(stats);
  showOverRender(stats.over);
  $('save-server').disabled = !stats.save_path;
  $('save-server').title = stats.save_path ? `writes ${stats.save_path}` : 'start phongcl serve with --save FILE';
}

// Light groups: each one a term of its own, soloed or muted by the server (the other lights, or the
// muted group's, shaded at colour 0). The controls are rebuilt only when the groups change.
function showLightGroups(stats) {
  const groups = stats.light_groups || [];
  if (groups.join('\n') !== state.lightGroups) {
    state.lightGroups = groups.join('\n');
    const aov = $('aov');
    for (const option of [...aov.options]) if (option.value.startsWith('group.')) option.remove();
    for (const name of groups) aov.append(el('option', { value: `group.${name}`, textContent: `group ${name}` }));
    $('solo').replaceChildren(el('option', { value: '', textContent: 'none' }),
      ...groups.map((name) => el('option', { value: name, textContent: name })));
    $('mute-groups').replaceChildren(...groups.map((name) => el('label', {}, [
      el('input', { type: 'checkbox', value: name, onchange: putLightGroupSettings }), ` mute ${name}`])));
    $('groups-row').hidden = groups.length === 0;
  }
  $('solo').value = stats.settings.solo || '';
  for (const box of $('mute-groups').querySelectorAll('input')) box.checked = (stats.settings.mute || []).includes(box.value);
}

// serve --over: the render every frame is composited over, and what the frame did with each of its
// light groups; a group's button selects its first light, which a drag on the image then moves.
function showOverRender(over) {
  $('over').hidden = !over;
  if (!over) return;
  $('over-render').textContent = `${over.render}${over.view_layer ? ` (view layer ${over.view_layer})` : ''}: ` +
    'unchanged groups stay as rendered; colour edits scale a group\'s pass; anything else re-shades it';
  const times = (v) => `×(${v.map((x) => Number(x).toFixed(2)).join(', ')})`;
  $('over-groups').replaceChildren(...over.groups.map((group) => {
    const first = (state.scene?.lights || []).findIndex((light) => light.group === group.name);
    const detail = group.change === 'scaled' ? ` ${times(group.scale)}`
      : group.fit ? ` (fit: diffuse ${times(group.fit.diffuse_gain)}, specular ${times(group.fit.specular_gain)}, ` +
        `residual ${Number(group.fit.residual).toFixed(3)})` : '';
    const pick = el('button', { type: 'button', textContent: 'select', disabled: first < 0,
                                title: first < 0 ? 'no point, spot or directional light in this group' : `drag moves light ${first}` });
    pick.addEventListener('click', () => { state.selectedLight = first; renderLights(); });
    const pass = group.pass ? '' : ' · no pass in the render';
    return el('li', {}, [el('div', { className: 'head' }, [
      el('span', { className: 'grow', textContent: `${group.name}: ${group.change}${detail}${pass}` }), pick])]);
  }));
}

async function putLightGroupSettings() {
  const mute = [...$('mute-groups').querySelectorAll('input:checked')].map((box) => box.value);
  const response = await fetch('api/settings', {
    method: 'PUT', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ solo: $('solo').value, mute }),
  });
  if (!response.ok) setStatus(await errorOf(response), true);
}

// ---- Widgets ----

function el(tag, attributes = {}, children = []) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) {
    if (key.startsWith('on')) node.addEventListener(key.slice(2), value);
    else if (key in node) node[key] = value;
    else node.setAttribute(key, value);
  }
  for (const child of children) node.append(child);
  return node;
}

const hex = (v) => Math.round(Math.min(1, Math.max(0, v)) * 255).toString(16).padStart(2, '0');

// An RGB value of any non-negative size as a colour picker (display space, color.js) and an
// intensity (the largest working-space component). Edits apply in order: a conversion that
// finishes after a newer edit's is dropped.
function colorInput(rgb, onChange, label) {
  const picker = el('input', { type: 'color', value: '#ffffff', title: `${label} colour`, disabled: true });
  const scale = el('input', { type: 'number', value: 1, min: 0, step: 0.05, title: `${label} intensity` });
  picker.dataset.role = `${label}-color`;
  scale.dataset.role = `${label}-intensity`;
  const space = () => state.scene.color_space || 'scene_linear';
  let edits = 0;
  colorManagement.toPicker(rgb, space()).then(({ unit, intensity }) => {
    if (edits > 0) return;  // already edited: keep what the user set
    picker.value = `#${unit.map(hex).join('')}`;
    scale.value = +intensity.toFixed(4);
  }).catch((error) => setStatus(`${label} colour: ${error.message}`, true)).finally(() => { picker.disabled = false; });
  const update = async () => {
    const edit = ++edits;
    const v = picker.value;
    const unit = [1, 3, 5].map((i) => parseInt(v.slice(i, i + 2), 16) / 255);
    try {
      const value = await colorManagement.fromPicker(unit, Number(scale.value), space());
      if (edit === edits) onChange(value);
    } catch (error) {
      setStatus(`${label} colour: ${error.message}`, true);
    }
  };
  picker.addEventListener('input', update);
  scale.addEventListener('input', update);
  return el('span', {}, [label + ' ', picker, scale]);
}

function vectorInput(values, onChange, role) {
  const inputs = values.map((v, i) => el('input', { type: 'number', value: +v.toFixed(4), step: 0.1, className: 'xyz' }));
  inputs.forEach((input, i) => { input.dataset.role = `${role}-${'xyz'[i]}`; });
  const update = () => onChange(inputs.map((i) => Number(i.value)));
  inputs.forEach((input) => input.addEventListener('input', update));
  return el('span', {}, [role + ' ', ...inputs]);
}

// Fields of the light model this page does not know yet get a plain editor, so new ones work.
function genericField(object, key, onChange) {
  const value = object[key];
  if (Array.isArray(value) && value.length === 3 && value.every((v) => typeof v === 'number'))
    return vectorInput(value, (v) => { object[key] = v; onChange(); }, key);
  if (typeof value === 'number') {
    const input = el('input', { type: 'number', value, step: 0.1 });
    input.addEventListener('input', () => { object[key] = Number(input.value); onChange(); });
    return el('label', {}, [key, input]);
  }
  if (typeof value === 'boolean') {
    const input = el('input', { type: 'checkbox', checked: value });
    input.addEventListener('change', () => { object[key] = input.checked; onChange(); });
    return el('label', {}, [key, input]);
  }
  const input = el('input', { type: 'text', value: JSON.stringify(value) });
  input.addEventListener('change', () => {
    try { object[key] = JSON.parse(input.value); onChange(); } catch { setStatus(`${key}: not JSON`, true); }
  });
  return el('label', {}, [key, input]);
}

// The light model's fields (scene/scene.h) with their own controls; any other gets genericField.
const lightKnownKeys = new Set(['type', 'position', 'direction', 'color', 'falloff', 'range', 'cone_angle_deg',
                                'penumbra_angle_deg', 'materials', 'rotation', 'strength']);
const falloffs = ['none', 'linear', 'quadratic', 'cubic'];
const defaultRange = 10;

// A slider with its value beside it; `bounds()` gives [min, max] as the other fields allow now.
function slider(label, role, value, bounds, step, onChange, unit = '°') {
  const input = el('input', { type: 'range', step, value });
  const shown = el('output', { textContent: `${value}${unit}` });
  input.dataset.role = role;
  const limit = () => { [input.min, input.max] = bounds(); };
  limit();
  input.value = value;
  input.addEventListener('input', () => { shown.textContent = `${input.value}${unit}`; onChange(Number(input.value)); });
  return { node: el('label', {}, [label, input, shown]), input, limit, shown };
}

// Falloff and range: point and spot lights only (the scene file refuses them on directional ones).
function attenuationControls(light) {
  const falloff = el('select', {}, falloffs.map((f) => el('option', { value: f, textContent: f })));
  falloff.value = light.falloff || 'none';
  falloff.dataset.role = 'falloff';
  falloff.addEventListener('change', () => {
    if (falloff.value === 'none') delete light.falloff; else light.falloff = falloff.value;
    edited();
  });
  const range = el('input', { type: 'number', min: 0.001, step: 0.5, value: light.range ?? defaultRange, disabled: light.range === undefined });
  range.dataset.role = 'range';
  const unlimited = el('input', { type: 'checkbox', checked: light.range === undefined, title: 'no range: the light reaches everywhere' });
  unlimited.dataset.role = 'no-range';
  const setRange = () => {
    range.disabled = unlimited.checked;
    if (unlimited.checked) delete light.range;
    else if (Number(range.value) > 0) light.range = Number(range.value);
    else return setStatus('range must be > 0', true);
    edited();
  };
  range.addEventListener('input', setRange);
  unlimited.addEventListener('change', setRange);
  return el('div', {}, [el('label', {}, ['falloff', falloff]), el('label', {}, ['range', range]),
                        el('label', {}, [unlimited, 'no range'])]);
}

// The spot's full cone angle A and soft edge P within the scene file's bounds: 0 < A < 180,
// P >= 0, A/2 + P <= 90 (a wider cone leaves less room for the edge, which is clamped to fit).
function coneControls(light) {
  let penumbra;
  const cone = slider('cone', 'cone', light.cone_angle_deg, () => [0.5, 179.5], 0.5, (a) => {
    light.cone_angle_deg = a;
    penumbra.limit();
    if ((light.penumbra_angle_deg ?? 0) > 90 - a / 2) {
      light.penumbra_angle_deg = 90 - a / 2;
      penumbra.input.value = light.penumbra_angle_deg;
      penumbra.shown.textContent = `${light.penumbra_angle_deg}°`;
    }
    edited();
  });
  penumbra = slider('penumbra', 'penumbra', light.penumbra_angle_deg ?? 0, () => [0, 90 - light.cone_angle_deg / 2], 0.25,
                    (p) => { light.penumbra_angle_deg = p; edited(); });
  return el('div', {}, [cone.node, penumbra.node]);
}

// The environment light's turn about Z and its strength (the scene file's bounds: any finite angle,
// a strength from 0 to 1e6; the slider offers 0 to 20, the JSON editor the rest).
function environmentControls(light) {
  return el('div', { className: 'environment' }, [
    slider('rotation', 'environment-rotation', light.rotation ?? 0, () => [-180, 180], 1,
           (r) => { light.rotation = r; edited(); }).node,
    slider('strength', 'environment-strength', light.strength ?? 1, () => [0, 20], 0.05,
           (s) => { light.strength = s; edited(); }, '').node,
  ]);
}

// Light linking: the materials a light reaches ("all" = no list in the scene file).
function linkControls(light) {
  const materials = state.scene.materials || [];
  const all = el('input', { type: 'checkbox', checked: light.materials === undefined });
  all.dataset.role = 'materials-all';
  const boxes = materials.map((m, i) => {
    const box = el('input', { type: 'checkbox', checked: light.materials === undefined || light.materials.includes(i),
                              disabled: light.materials === undefined });
    box.dataset.role = `material-${i}`;
    return box;
  });
  const update = () => {
    boxes.forEach((box) => { box.disabled = all.checked; if (all.checked) box.checked = true; });
    if (all.checked) delete light.materials;
    else light.materials = boxes.flatMap((box, i) => (box.checked ? [i] : []));
    edited();
  };
  all.addEventListener('change', update);
  boxes.forEach((box) => box.addEventListener('change', update));
  return el('div', { className: 'links' }, [
    'lights materials', el('label', {}, [all, 'all']),
    ...boxes.map((box, i) => el('label', { title: materials[i].name || '' }, [box, String(i)])),
  ]);
}

function renderLights() {
  const list = $('lights');
  list.replaceChildren();
  (state.scene.lights || []).forEach((light, index) => {
    const enabled = el('input', { type: 'checkbox', checked: !state.disabled.has(index),
                                  title: 'on/off (a light switched off is left out of what is saved)' });
    enabled.addEventListener('change', () => {
      if (enabled.checked) state.disabled.delete(index); else state.disabled.add(index);
      edited();
    });
    const remove = el('button', { type: 'button', textContent: '✕', title: 'remove' });
    remove.addEventListener('click', (event) => {
      event.stopPropagation();
      state.scene.lights.splice(index, 1);
      state.disabled = new Set([...state.disabled].filter((i) => i !== index).map((i) => (i > index ? i - 1 : i)));
      state.selectedLight = Math.min(state.selectedLight, state.scene.lights.length - 1);
      renderLights();
      edited();
    });
    const environment = light.type === 'environment';
    const vectors = environment ? [] : light.type === 'directional' ? ['direction'] : light.type === 'spot' ? ['position', 'direction'] : ['position'];
    const item = el('li', { className: index === state.selectedLight ? 'selected' : '' }, [
      el('div', { className: 'head' }, [enabled, el('span', { className: 'grow', textContent: `${index}: ${light.type}` }), remove]),
      // A map's world has no colour of its own: its image is the light.
      ...(environment && light.file !== undefined ? [] : [colorInput(light.color || [1, 1, 1], (c) => { light.color = c; edited(); }, 'light')]),
      ...vectors.map((key) => el('div', {}, [vectorInput(light[key] || [0, 0, 0], (v) => { light[key] = v; edited(); }, key)])),
      ...(environment ? [environmentControls(light)] : []),
      ...(light.type === 'directional' || environment ? [] : [attenuationControls(light)]),
      ...(light.type === 'spot' ? [coneControls(light)] : []),
      ...(environment ? [] : [linkControls(light)]),
      ...Object.keys(light).filter((k) => !lightKnownKeys.has(k)).map((k) => genericField(light, k, edited)),
    ]);
    item.dataset.light = index;
    item.addEventListener('click', () => {
      if (state.selectedLight === index) return;
      state.selectedLight = index;
      list.querySelectorAll('li').forEach((li) => li.classList.toggle('selected', Number(li.dataset.light) === index));
    });
    list.append(item);
  });
}

const newLights = {
  point: () => ({ type: 'point', position: [0, 2, 2], color: [1, 1, 1] }),
  directional: () => ({ type: 'directional', direction: [0, -1, -1], color: [0.5, 0.5, 0.5] }),
  spot: () => ({ type: 'spot', position: [0, 2, 2], direction: [0, -1, -1], color: [1, 1, 1], cone_angle_deg: 40,
                 penumbra_angle_deg: 5 }),
};

function addLight(type) {
  state.scene.lights = state.scene.lights || [];
  state.scene.lights.push(newLights[type]());
  state.selectedLight = state.scene.lights.length - 1;
  renderLights();
  edited();
}

function renderMaterials() {
  const list = $('materials');
  list.replaceChildren();
  (state.scene.materials || []).forEach((material, index) => {
    const number = (key, fallback, range) => {
      const input = el('input', { type: 'number', value: material[key] ?? fallback, ...range });
      input.addEventListener('input', () => { material[key] = Number(input.value); edited(); });
      return el('label', {}, [key, input]);
    };
    const colour = (key, fallback) =>
      el('div', {}, [colorInput(material[key] || fallback, (c) => { material[key] = c; edited(); }, key)]);
    // A principled material has no kd, ks or shininess (the scene refuses them): its own inputs instead.
    const fields = material.specular_model === 'principled'
      ? [colour('base_color', [0.8, 0.8, 0.8]), number('metallic', 0, { min: 0, max: 1, step: 0.05 }),
         number('roughness', 0.5, { min: 0, max: 1, step: 0.05 }),
         ...(material.version === 2 ? [number('ior', 1.5, { min: 1, max: 1000, step: 0.05 }),
           number('specular_ior_level', 0.5, { min: 0, step: 0.05 }),
           number('diffuse_roughness', 0, { min: 0, max: 1, step: 0.05 })] : [])]
      : [...['ka', 'kd', 'ks'].map((k) => colour(k, [0, 0, 0])), number('shininess', 1, { min: 0, step: 1 })];
    const item = el('li', { className: index === state.selectedMaterial ? 'selected' : '' }, [
      el('div', { className: 'head' }, [el('span', { className: 'grow', textContent: `${index}: ${material.name || ''}` })]),
      ...fields,
    ]);
    item.dataset.material = index;
    list.append(item);
  });
}

// ---- Dragging a light over the image ----

function pixelUnder(event) {
  const view = $('view');
  const box = view.getBoundingClientRect();
  const [width, height] = state.imageSize;
  const x = Math.floor(((event.clientX - box.left) / box.width) * width);
  const y = Math.floor(((event.clientY - box.top) / box.height) * height);
  return x >= 0 && y >= 0 && x < width && y < height ? [x, y] : null;
}

let pendingPick = null;

async function pickAt(pixel, apply) {
  pendingPick = { pixel, apply };
  if (state.picking) return;
  state.picking = true;
  while (pendingPick) {
    const { pixel: [x, y], apply: use } = pendingPick;
    pendingPick = null;
    const response = await fetch(`api/pick?x=${x}&y=${y}`);
    if (response.ok) use(await response.json());
  }
  state.picking = false;
}

// A point or spot light goes `distance` along the normal (a spot aims back at the point); a
// directional light shines along -normal.
function placeSelectedLight(pick) {
  const light = (state.scene.lights || [])[state.selectedLight];
  if (!pick.shaded || !light) return;
  const distance = Number($('distance').value);
  if (light.type !== 'point') light.direction = pick.normal.map((n) => -n);
  if (light.type !== 'directional') light.position = pick.position.map((p, i) => p + distance * pick.normal[i]);
  edited();
  const item = $('lights').querySelector(`li[data-light="${state.selectedLight}"]`);
  for (const key of ['position', 'direction'])
    if (item && light[key])
      light[key].forEach((v, i) => {
        const input = item.querySelector(`input[data-role="${key}-${'xyz'[i]}"]`);
        if (input) input.value = +v.toFixed(4);
      });
}

function selectMaterialAt(pick) {
  state.selectedMaterial = pick.shaded ? pick.material : -1;
  $('materials').querySelectorAll('li').forEach((li) => li.classList.toggle('selected', Number(li.dataset.material) === state.selectedMaterial));
  const item = $('materials').querySelector(`li[data-material="${state.selectedMaterial}"]`);
  if (item) item.scrollIntoView({ block: 'nearest' });
}

function mode() { return document.querySelector('input[name=mode]:checked').value; }

function setUpImageInput() {
  const view = $('view');
  let dragging = false;
  view.addEventListener('pointerdown', (event) => {
    const pixel = pixelUnder(event);
    if (!pixel) return;
    if (mode() === 'material') return pickAt(pixel, selectMaterialAt);
    dragging = true;
    try { view.setPointerCapture(event.pointerId); } catch { /* a synthetic event's pointer is not active */ }
    pickAt(pixel, placeSelectedLight);
  });
  view.addEventListener('pointermove', (event) => {
    if (!dragging) return;
    const pixel = pixelUnder(event);
    if (pixel) pickAt(pixel, placeSelectedLight);
  });
  const end = () => { dragging = false; };
  view.addEventListener('pointerup', end);
  view.addEventListener('pointercancel', end);
}

// ---- Save ----

async function downloadScene() {
  const blob = new Blob([JSON.stringify(sceneToSend(), null, 2) + '\n'], { type: 'application/json' });
  const link = el('a', { href: URL.createObjectURL(blob), download: 'scene.json' });
  link.click();
  setTimeout(() => URL.revokeObjectURL(link.href), 1000);
}

async function saveOnServer() {
  const response = await fetch('api/save', { method: 'POST' });
  if (response.ok) {
    const saved = await response.json();
    setStatus(`saved ${saved.saved} (${saved.bytes} bytes)`, false);
  } else {
    setStatus(await errorOf(response), true);
  }
}

// ---- Start ----

async function start() {
  $('add-point').addEventListener('click', () => addLight('point'));
  $('add-directional').addEventListener('click', () => addLight('directional'));
  $('add-spot').addEventListener('click', () => addLight('spot'));
  for (const id of ['aov', 'format', 'fit']) $(id).addEventListener('change', viewChanged);
  await colorManagement.load(viewChanged);
  window.addEventListener('resize', viewChanged);
  $('exposure').addEventListener('input', () => { $('exposure-value').textContent = $('exposure').value; viewChanged(); });
  $('split').addEventListener('input', () => { $('split-value').textContent = `${$('split').value}%`; drawView(); });
  for (const setting of ['precision', 'shadows']) {
    $(setting).addEventListener('change', async () => {
      const response = await fetch('api/settings', {
        method: 'PUT', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ [setting]: $(setting).value }),
      });
      if (!response.ok) setStatus(await errorOf(response), true);
    });
  }
  $('solo').addEventListener('change', putLightGroupSettings);
  $('download-scene').addEventListener('click', downloadScene);
  $('save-server').addEventListener('click', saveOnServer);
  setUpImageInput();
  await loadScene();
  await refreshKernel();
  pollFrames();
  setInterval(refreshKernel, 2000);
}

start();
