// Three.js objects for one parsed network: patches (two meshes sharing the
// positions, one per side, for two-sided colouring), chains as lines, corners
// as points, and one mesh per cell for the exploded view.
import * as THREE from 'three';
import { LineSegments2 } from 'three/addons/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/addons/lines/LineSegmentsGeometry.js';
import { LineMaterial } from 'three/addons/lines/LineMaterial.js';
import { shades, cellColor } from './palette.js';

function material(flat, side, clip) {
  // Polygon offset pushes walls back a little so chains lying on them win
  // the depth test and stay visible.
  const opts = { vertexColors: true, side, clippingPlanes: clip, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 };
  return flat ? new THREE.MeshBasicMaterial(opts) : new THREE.MeshLambertMaterial(opts);
}

/** Non-indexed triangle soup: every triangle owns its three vertices so each
 * face can have its own colour and flat normal. */
function soup(net, triIds) {
  const pos = new Float32Array(triIds.length * 9);
  triIds.forEach((t, n) => {
    for (let c = 0; c < 3; c++) {
      const p = net.tris[3 * t + c];
      pos[9 * n + 3 * c] = net.pos[3 * p];
      pos[9 * n + 3 * c + 1] = net.pos[3 * p + 1];
      pos[9 * n + 3 * c + 2] = net.pos[3 * p + 2];
    }
  });
  return pos;
}

export class NetworkScene {
  constructor(net, { flat = false } = {}) {
    this.net = net;
    this.flat = flat;
    this.group = new THREE.Group();
    this.clipPlanes = [];
    this.colorBy = 'label';
    this.hidden = new Set();
    this.explode = 0;

    const allTris = Array.from({ length: net.triFace.length }, (_, i) => i);
    const position = new THREE.BufferAttribute(soup(net, allTris), 3);
    this.frontGeom = new THREE.BufferGeometry();
    this.backGeom = new THREE.BufferGeometry();
    for (const g of [this.frontGeom, this.backGeom]) {
      g.setAttribute('position', position);
      g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(position.count * 3), 3));
    }
    this.frontGeom.computeVertexNormals();
    this.backGeom.setAttribute('normal', this.frontGeom.getAttribute('normal'));
    this.front = new THREE.Mesh(this.frontGeom, material(flat, THREE.FrontSide, this.clipPlanes));
    this.back = new THREE.Mesh(this.backGeom, material(flat, THREE.BackSide, this.clipPlanes));
    this.front.userData.side = '+';
    this.back.userData.side = '-';
    this.patchGroup = new THREE.Group();
    this.patchGroup.add(this.front, this.back);

    // Chains: consecutive point pairs along each chain, drawn as screen-space
    // wide lines (plain WebGL lines are one pixel wide).
    const seg = [];
    for (const ch of net.chains) {
      for (let k = 0; k + 1 < ch.length; k++) {
        for (const p of [ch[k], ch[k + 1]]) seg.push(net.pos[3 * p], net.pos[3 * p + 1], net.pos[3 * p + 2]);
      }
    }
    const chainGeom = new LineSegmentsGeometry();
    if (seg.length) chainGeom.setPositions(seg);
    this.chainMaterial = new LineMaterial({ color: 0x151515, linewidth: 3, clippingPlanes: this.clipPlanes });
    this.chains = new LineSegments2(chainGeom, this.chainMaterial);
    this.hasChains = seg.length > 0;
    this.chains.visible = this.hasChains;
    const cornerPos = new Float32Array(net.corners.length * 3);
    net.corners.forEach((p, i) => cornerPos.set(net.pos.subarray(3 * p, 3 * p + 3), 3 * i));
    const cornerGeom = new THREE.BufferGeometry();
    cornerGeom.setAttribute('position', new THREE.BufferAttribute(cornerPos, 3));
    this.corners = new THREE.Points(
      cornerGeom,
      new THREE.PointsMaterial({ color: 0xd01010, size: 9, sizeAttenuation: false, clippingPlanes: this.clipPlanes }),
    );

    this.cellGroup = this.buildCells();
    this.cellGroup.visible = false;
    this.group.add(this.patchGroup, this.chains, this.corners, this.cellGroup);
    this.recolor();
  }

  /** One mesh per cell: its bounding faces, wound so the normal points out of
   * the cell (faces are CCW seen from their positive side, whose cell is
   * c_pos, so for c_pos the winding is reversed). */
  buildCells() {
    const net = this.net;
    const group = new THREE.Group();
    const center = new THREE.Vector3(
      (net.box[0] + net.box[3]) / 2, (net.box[1] + net.box[4]) / 2, (net.box[2] + net.box[5]) / 2);
    const perCell = net.cells.map(() => []);
    net.triFace.forEach((f, t) => {
      const [cp, cn] = net.faceCells[f] || [-1, -1];
      if (cp >= 0 && perCell[cp]) perCell[cp].push([t, true]);
      if (cn >= 0 && perCell[cn]) perCell[cn].push([t, false]);
    });
    perCell.forEach((list, c) => {
      if (!list.length) return;
      const pos = soup(net, list.map(([t]) => t));
      list.forEach(([, reverse], n) => {
        if (!reverse) return;
        for (let a = 0; a < 3; a++) {
          const tmp = pos[9 * n + 3 + a];
          pos[9 * n + 3 + a] = pos[9 * n + 6 + a];
          pos[9 * n + 6 + a] = tmp;
        }
      });
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      g.computeVertexNormals();
      g.computeBoundingBox();
      const cc = new THREE.Vector3();
      g.boundingBox.getCenter(cc);
      const col = cellColor(c);
      const mat = this.flat
        ? new THREE.MeshBasicMaterial({ color: col, side: THREE.DoubleSide, clippingPlanes: this.clipPlanes })
        : new THREE.MeshLambertMaterial({ color: col, side: THREE.DoubleSide, clippingPlanes: this.clipPlanes });
      const mesh = new THREE.Mesh(g, mat);
      mesh.userData = { cell: c, tris: list.map(([t]) => t), dir: cc.sub(center) };
      group.add(mesh);
    });
    return group;
  }

  /** Key used for colouring a patch: its label, or its id. */
  patchColorIndex(p) {
    if (this.colorBy === 'patch') return p;
    return this.net.labels.indexOf(this.net.patchKeys[p]);
  }

  /** Writes face colours (front = positive side, back = negative side) and
   * hides faces whose label is toggled off by collapsing their triangles. */
  recolor() {
    const net = this.net;
    const fc = this.frontGeom.getAttribute('color');
    const bc = this.backGeom.getAttribute('color');
    const cache = new Map();
    const visible = [];
    for (let t = 0; t < net.triFace.length; t++) {
      const p = net.facePatch[net.triFace[t]];
      const k = this.patchColorIndex(p);
      if (!cache.has(k)) cache.set(k, shades(k));
      const { front, back } = cache.get(k);
      for (let c = 0; c < 3; c++) {
        fc.setXYZ(3 * t + c, front.r, front.g, front.b);
        bc.setXYZ(3 * t + c, back.r, back.g, back.b);
      }
      if (!this.hidden.has(net.patchKeys[p])) visible.push(3 * t, 3 * t + 1, 3 * t + 2);
    }
    fc.needsUpdate = true;
    bc.needsUpdate = true;
    this.frontGeom.setIndex(visible);
    this.backGeom.setIndex(visible);
    for (const mesh of this.cellGroup.children) {
      const labels = new Set(mesh.userData.tris.map((t) => net.patchKeys[net.facePatch[net.triFace[t]]]));
      mesh.visible = [...labels].some((l) => !this.hidden.has(l));
    }
  }

  /** Exploded view: t = 0 shows the network; t > 0 moves each cell away from
   * the centre by t times its offset. */
  setExplode(t) {
    this.explode = t;
    const on = t > 0;
    this.cellGroup.visible = on;
    this.patchGroup.visible = !on;
    this.chains.visible = !on && this.showChains !== false && this.hasChains;
    this.corners.visible = !on && this.showCorners !== false;
    for (const mesh of this.cellGroup.children) {
      mesh.position.copy(mesh.userData.dir).multiplyScalar(1.5 * t);
    }
  }

  /** Palette actually used now: one entry per colour index in use. */
  palette() {
    const seen = new Map();
    for (let p = 0; p < this.net.patches.length; p++) {
      const k = this.patchColorIndex(p);
      if (!seen.has(k)) seen.set(k, { index: k, label: this.net.patchKeys[p], ...shades(k) });
    }
    return [...seen.values()];
  }
}
