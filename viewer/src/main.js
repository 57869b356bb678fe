// Septa viewer entry point. The data comes from data.js, a script that sets
// window.__SEPTA_DATA (written next to index.html by `septa view` and
// `septa.view`), so the page works from file:// with no server and no network.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { parseNetwork, labelKey, cellText } from './network.js';
import { NetworkScene } from './scene.js';
import { buildPanel } from './panel.js';
import { rgb255 } from './palette.js';

function start() {
  const data = window.__SEPTA_DATA;
  const info = document.getElementById('info');
  if (!data || !data.network) {
    info.textContent = 'No data: data.js did not define window.__SEPTA_DATA.network.';
    window.__septaReady = true;
    return;
  }
  const params = new URLSearchParams(location.search);
  const flat = params.get('flat') === '1';
  const net = parseNetwork(data.network);

  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: !flat, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.localClippingEnabled = true;
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf2f3f5);
  scene.add(new THREE.AmbientLight(0xffffff, 1.5));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  scene.add(sun);

  const ns = new NetworkScene(net, { flat });
  scene.add(ns.group);

  // Camera: z up (the data's convention), looking down at the box from
  // above a corner so walls meeting along vertical lines are all visible.
  const b = net.box;
  const center = new THREE.Vector3((b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2);
  const radius = Math.max(1e-9, 0.5 * Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]));
  const camera = new THREE.PerspectiveCamera(35, 1, radius / 100, radius * 100);
  camera.up.set(0, 0, 1);
  camera.position.copy(center).add(new THREE.Vector3(1.5, -2.3, 2.4).normalize().multiplyScalar(3.6 * radius));
  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(center);
  controls.update();

  const clip = new THREE.Plane(new THREE.Vector3(1, 0, 0), 0);
  const clipState = { on: false, axis: 0, at: 0.5, flip: false };
  function applyClip() {
    const n = new THREE.Vector3();
    n.setComponent(clipState.axis, clipState.flip ? 1 : -1);
    const lo = b[clipState.axis];
    const hi = b[3 + clipState.axis];
    const at = lo + clipState.at * (hi - lo);
    // Keep the points with n . x + constant >= 0.
    clip.set(n, clipState.flip ? -at : at);
    ns.clipPlanes.length = 0;
    if (clipState.on) ns.clipPlanes.push(clip);
  }

  let pending = false;
  function render() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      const w = canvas.clientWidth;
      const h = canvas.clientHeight;
      if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
        renderer.setSize(w, h, false);
        ns.chainMaterial.resolution.set(w, h);
        camera.aspect = w / Math.max(1, h);
        camera.updateProjectionMatrix();
      }
      sun.position.copy(camera.position).add(new THREE.Vector3(0, 0, radius));
      renderer.render(scene, camera);
      window.__septaFrames = (window.__septaFrames || 0) + 1;
      // Ready once a frame is drawn and the browser had a chance to show it.
      if (!window.__septaReady) requestAnimationFrame(() => { window.__septaReady = true; });
    });
  }
  controls.addEventListener('change', render);
  window.addEventListener('resize', render);

  // Picking: the nearest face under the cursor, on either side.
  const ray = new THREE.Raycaster();
  ray.params.Line.threshold = radius * 0.01;
  function pick(x, y) {
    const r = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - r.left) / r.width) * 2 - 1, -((y - r.top) / r.height) * 2 + 1);
    ray.setFromCamera(ndc, camera);
    const targets = ns.explode > 0 ? ns.cellGroup.children.filter((m) => m.visible) : [ns.front, ns.back];
    const hit = ray.intersectObjects(targets, false).find((h) => clipState.on ? clip.distanceToPoint(h.point) >= 0 : true);
    if (!hit) return null;
    let tri = hit.faceIndex;
    const out = {};
    if (hit.object.userData.cell !== undefined) {
      out.cell = hit.object.userData.cell;
      tri = hit.object.userData.tris[tri];
    } else {
      out.side = hit.object.userData.side;
    }
    out.face = net.triFace[tri];
    out.patch = net.facePatch[out.face];
    out.patchLabel = net.patches[out.patch]?.label;
    out.faceCells = net.faceCells[out.face];
    if (out.side) out.cell = out.side === '+' ? out.faceCells[0] : out.faceCells[1];
    out.cellLabel = out.cell >= 0 ? net.cells[out.cell]?.label : undefined;
    return out;
  }
  function showPick(p) {
    if (!p) {
      info.textContent = 'Nothing here.';
      return;
    }
    const side = p.side ? ` (${p.side === '+' ? 'positive' : 'negative'} side)` : '';
    // The label in the result's names (a scene's function and region
    // names, a label table's), when they say more than the ids.
    const key = net.patchKeys[p.patch];
    const named = key !== undefined && key !== labelKey(p.patchLabel) ? `: ${key}` : '';
    const cellName = Array.isArray(p.cellLabel) ? cellText(p.cellLabel, net.names, net.mode) : '';
    const cellNamed = cellName && cellName !== String(p.cellLabel[0]) && (net.mode === 'regions' || net.mode === 'mi') ? ` (${cellName})` : '';
    info.textContent =
      `patch ${p.patch} label ${JSON.stringify(p.patchLabel)}${named}${side}\n` +
      `face ${p.face}, cells [+ ${p.faceCells[0]}, - ${p.faceCells[1]}]\n` +
      (p.cell >= 0
        ? (net.mode === 'regions' && Array.isArray(p.cellLabel)
          ? `cell ${p.cell}: region ${p.cellLabel[0]}${cellNamed}`
          : `cell ${p.cell} label ${JSON.stringify(p.cellLabel)}${cellNamed}`)
        : 'cell: outside');
  }
  let down = null;
  canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  canvas.addEventListener('pointerup', (e) => {
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4) showPick(pick(e.clientX, e.clientY));
    down = null;
  });

  const api = {
    net,
    render,
    setExplode(t) { ns.setExplode(t); render(); },
    setColorBy(mode) { ns.colorBy = mode; ns.recolor(); render(); },
    setLabelVisible(key, on) { if (on) ns.hidden.delete(key); else ns.hidden.add(key); ns.recolor(); render(); },
    setClip(opts) { Object.assign(clipState, opts); applyClip(); render(); },
    setShow(what, on) {
      if (what === 'chains') ns.showChains = on;
      if (what === 'corners') ns.showCorners = on;
      if (what === 'patches') ns.patchGroup.visible = on && ns.explode === 0;
      ns.setExplode(ns.explode);
      if (what === 'patches') ns.patchGroup.visible = on && ns.explode === 0;
      render();
    },
    pick(x, y) { const p = pick(x, y); showPick(p); return p; },
    /** Screen colours in use: [{label, front:[r,g,b], back:[r,g,b]}] (0..255). */
    palette() {
      return ns.palette().map((e) => ({ index: e.index, label: e.label, front: rgb255(e.front), back: rgb255(e.back) }));
    },
  };
  window.__septa = api;
  buildPanel(data, net, ns, api);
  render();
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
