// phongcl serve's colour management on the page: the OCIO config's displays, views and looks as
// the View controls (what every frame is encoded with), and the colour pickers' conversions: a
// picker shows and takes display-space colours (the config's picker space, e.g. sRGB), the scene
// holds its own space's values (its "color_space", else the working space). Conversions are the
// server's (GET /api/color), so they are OpenColorIO's, whatever the config.
'use strict';

const colorManagement = (() => {
  let config = null;  // GET /api/colors
  const conversions = new Map();  // "from>to:r,g,b" -> Promise of [r, g, b]

  function display() {
    return (config && config.displays.find((d) => d.name === document.getElementById('display').value)) || null;
  }

  function fillSelect(select, names, chosen) {
    select.replaceChildren(...names.map((name) => Object.assign(document.createElement('option'), { value: name, textContent: name })));
    if (names.includes(chosen)) select.value = chosen;
  }

  // The views of the chosen display, keeping the current view where the display has it.
  function fillViews() {
    const d = display();
    const views = document.getElementById('view');
    fillSelect(views, d ? d.views : [], views.value || (d && d.default_view));
    if (d && !d.views.includes(views.value)) views.value = d.default_view;
  }

  // Fills the display, view and look controls from the config; `changed` runs after a user's change.
  async function load(changed) {
    const response = await fetch('api/colors');
    config = await response.json();
    const displays = document.getElementById('display');
    fillSelect(displays, config.displays.map((d) => d.name), config.default_display);
    fillViews();
    fillSelect(document.getElementById('look'), ['None', ...config.looks], 'None');
    document.getElementById('look-row').hidden = config.looks.length === 0;
    document.getElementById('color-config').textContent = `${config.config} · working space ${config.working_space}`;
    displays.addEventListener('change', () => { fillViews(); changed(); });
    for (const id of ['view', 'look']) document.getElementById(id).addEventListener('change', changed);
  }

  // The display parameters of an image request.
  function query() {
    const look = document.getElementById('look').value;
    const parts = [['display', document.getElementById('display').value], ['view', document.getElementById('view').value],
                   ['exposure', document.getElementById('exposure').value]];
    if (look && look !== 'None') parts.push(['look', look]);
    return parts.filter(([, v]) => v).map(([k, v]) => `${k}=${encodeURIComponent(v)}`).join('&');
  }

  function convert(rgb, from, to) {
    if (from === to) return Promise.resolve(rgb);
    const key = `${from}>${to}:${rgb.join(',')}`;
    if (!conversions.has(key)) {
      const url = `api/color?rgb=${rgb.join(',')}&from=${encodeURIComponent(from)}&to=${encodeURIComponent(to)}`;
      conversions.set(key, fetch(url).then(async (response) => {
        if (!response.ok) throw new Error((await response.json()).error);
        return (await response.json()).rgb;
      }));
    }
    return conversions.get(key);
  }

  const pickerSpace = () => (display() ? display().picker_space : 'scene_linear');
  const working = 'scene_linear';

  // A scene colour as a picker's colour and an intensity (the largest working-space component):
  // { unit: [r, g, b] in the picker's space, 0..1, intensity }.
  async function toPicker(sceneRgb, sceneSpace) {
    const linear = await convert(sceneRgb, sceneSpace, working);
    const intensity = Math.max(...linear);
    const unit = intensity > 0 ? linear.map((c) => c / intensity) : [1, 1, 1];
    return { unit: await convert(unit, working, pickerSpace()), intensity };
  }

  // A picker's colour times an intensity, in the scene's space.
  async function fromPicker(unit, intensity, sceneSpace) {
    const linear = (await convert(unit, pickerSpace(), working)).map((c) => c * intensity);
    return convert(linear, working, sceneSpace);
  }

  return { load, query, toPicker, fromPicker };
})();
