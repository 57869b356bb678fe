// The side panel: counts, display toggles, exploded-view slider, clipping
// plane and one visibility toggle per patch label.
import { shades, rgb255 } from './palette.js';

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'on') for (const [ev, f] of Object.entries(v)) e.addEventListener(ev, f);
    else if (k in e) e[k] = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function checkbox(id, text, checked, onChange) {
  const box = el('input', { type: 'checkbox', id, checked, on: { change: (e) => onChange(e.target.checked) } });
  return el('label', { htmlFor: id }, box, ' ', text);
}

export function buildPanel(data, net, ns, api) {
  const panel = document.getElementById('panel');
  const title = data.title || 'Septa';
  panel.append(el('h1', {}, title));
  panel.append(el('div', { className: 'mode' }, `mode: ${net.mode}`));

  const counts = el('table', { className: 'counts' });
  // Scalars as they are; nested summaries (e.g. a region job's "network")
  // one level deep; lists by their length.
  const row = (k, v) => counts.append(el('tr', {}, el('td', {}, k), el('td', {}, String(v))));
  for (const [k, v] of Object.entries(net.counts)) {
    if (k === 'seconds') continue;
    if (Array.isArray(v)) row(k, `${v.length} item(s)`);
    else if (v && typeof v === 'object') {
      for (const [k2, v2] of Object.entries(v)) if (typeof v2 !== 'object') row(`${k}.${k2}`, v2);
    } else row(k, v);
  }
  panel.append(counts);

  panel.append(el('h2', {}, 'Show'));
  panel.append(checkbox('show-patches', 'patches', true, (on) => api.setShow('patches', on)));
  panel.append(checkbox('show-chains', `chains (${net.chains.length})`, true, (on) => api.setShow('chains', on)));
  panel.append(checkbox('show-corners', `corners (${net.corners.length})`, true, (on) => api.setShow('corners', on)));
  const colorBy = el('select', { id: 'color-by', on: { change: (e) => { api.setColorBy(e.target.value); refreshSwatches(); } } },
    el('option', { value: 'label' }, 'colour by label'), el('option', { value: 'patch' }, 'colour by patch'));
  panel.append(el('div', {}, colorBy));

  panel.append(el('h2', {}, 'Exploded cells'));
  const explode = el('input', {
    type: 'range', id: 'explode', min: '0', max: '1', step: '0.01', value: '0',
    on: { input: (e) => api.setExplode(Number(e.target.value)) },
  });
  panel.append(el('div', {}, explode, ` ${net.cells.length} cells`));

  panel.append(el('h2', {}, 'Clipping plane'));
  const axis = el('select', { id: 'clip-axis', on: { change: (e) => api.setClip({ axis: Number(e.target.value) }) } },
    el('option', { value: '0' }, 'x'), el('option', { value: '1' }, 'y'), el('option', { value: '2' }, 'z'));
  const at = el('input', {
    type: 'range', id: 'clip-at', min: '0', max: '1', step: '0.005', value: '0.5',
    on: { input: (e) => api.setClip({ at: Number(e.target.value) }) },
  });
  panel.append(checkbox('clip-on', 'clip', false, (on) => api.setClip({ on })), ' ', axis,
    checkbox('clip-flip', 'flip', false, (flip) => api.setClip({ flip })), el('div', {}, at));

  panel.append(el('h2', {}, 'Labels'));
  const list = el('div', { id: 'labels' });
  const swatches = [];
  net.labels.forEach((key, i) => {
    const sw = el('span', { className: 'swatch' });
    swatches.push([sw, key]);
    list.append(el('div', {}, sw, checkbox(`label-${i}`, key, true, (on) => api.setLabelVisible(key, on))));
  });
  panel.append(list);
  function refreshSwatches() {
    for (const [sw, key] of swatches) {
      const c = rgb255(shades(net.labels.indexOf(key)).front);
      sw.style.background = ns.colorBy === 'label' ? `rgb(${c.join(',')})` : 'transparent';
    }
  }
  refreshSwatches();
  panel.append(el('p', { className: 'hint' }, 'Drag to orbit, scroll to zoom, click a wall to pick it. Light shade: positive side; dark shade: negative side.'));
}
