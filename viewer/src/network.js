// Reads the job output contract (network.json, see scripts/make_fixture.py)
// into flat typed arrays the renderer can use directly.
//
// Polygons are fan-triangulated: output faces are convex (each is a piece of a
// plane inside one tet, or a planar cut-face), so a fan is a valid
// triangulation and keeps the face's CCW orientation (seen from its positive
// side) in every triangle.

/** A function's name from the result's `names` (a scene's `"name"`), or
 * `f<index>` when it has none (a scene names unnamed functions by index). */
function functionName(f, names) {
  const n = names?.functions?.[f];
  return n !== undefined && n !== null && String(n) !== String(f) ? String(n) : `f${f}`;
}

/** A region's (label's, material's) name, or its id. */
function regionName(r, names, mode) {
  const n = names?.regions?.[String(r)];
  if (n !== undefined && n !== null) return String(n);
  // MI: a material is a function; named as the function when it has a name
  if (mode === 'mi' && r >= 0 && names?.functions?.[r] !== undefined && String(names.functions[r]) !== String(r)) {
    return String(names.functions[r]);
  }
  return String(r);
}

/** Stable string key of a label (patch label pair or cell label), in the
 * result's names where it has them: IA patches by their function's name,
 * MI and region walls as `a|b` of their materials' or regions' names. */
export function labelKey(label, names = null, mode = 'ia') {
  if (!Array.isArray(label)) return String(label);
  // IA patches carry [function, -1] (or [f, f]); show just the function.
  if (label.length === 2 && (label[1] < 0 || label[0] === label[1])) return functionName(label[0], names);
  if (mode === 'mi' || mode === 'regions') return label.map((r) => regionName(r, names, mode)).join('|');
  return label.join('|');
}

/** A cell's label in words: regions and MI by name, IA as its sign vector. */
export function cellText(label, names, mode) {
  if (!Array.isArray(label)) return String(label);
  if ((mode === 'regions' || mode === 'mi') && label.length >= 1) return regionName(label[0], names, mode);
  return JSON.stringify(label);
}

/** Parses a network object; returns typed arrays plus the raw lists. */
export function parseNetwork(net) {
  const points = net.points || [];
  const faces = net.faces || [];
  const facePatch = net.face_patch || faces.map(() => 0);
  const faceCells = net.face_cells || faces.map(() => [-1, -1]);
  const patches = net.patches || [];
  const cells = net.cells || [];

  const pos = new Float32Array(points.length * 3);
  points.forEach((p, i) => pos.set(p, 3 * i));

  // Triangles (as point ids) and the face each one comes from.
  let triCount = 0;
  for (const f of faces) triCount += Math.max(0, f.length - 2);
  const tris = new Uint32Array(triCount * 3);
  const triFace = new Int32Array(triCount);
  let t = 0;
  faces.forEach((f, fi) => {
    for (let k = 1; k + 1 < f.length; k++) {
      tris[3 * t] = f[0];
      tris[3 * t + 1] = f[k];
      tris[3 * t + 2] = f[k + 1];
      triFace[t] = fi;
      t++;
    }
  });

  const names = net.names || null;
  const mode = net.mode || 'ia';
  const patchKeys = patches.map((p) => labelKey(p.label ?? [facePatch.indexOf(p), -1], names, mode));
  const labels = [...new Set(patchKeys)];

  const box = new Float64Array([Infinity, Infinity, Infinity, -Infinity, -Infinity, -Infinity]);
  for (const p of points) {
    for (let a = 0; a < 3; a++) {
      box[a] = Math.min(box[a], p[a]);
      box[3 + a] = Math.max(box[3 + a], p[a]);
    }
  }
  if (!points.length) box.set([0, 0, 0, 1, 1, 1]);

  return {
    mode,
    names,
    pos,
    faces,
    tris,
    triFace,
    facePatch,
    faceCells,
    patches,
    patchKeys,
    labels,
    cells,
    chains: net.chains || [],
    corners: net.corners || [],
    counts: net.counts || {},
    seconds: net.seconds || {},
    box,
  };
}
