//! Remeshing a result as it was written (`septa remesh OUT L`, Python's
//! `Network.remesh`): its polygons, chains and corners, with no grid, no
//! vertex keys and no formulas left. The vertices stay on the unremeshed
//! patches (closest point on their triangles, a chain vertex on its chain:
//! the sampled-input placement of `mod.rs`), the box is the one the
//! patches' free borders reach (`used_box`), and the result is certified and refused as
//! [`super::remesh_network`]'s is.

use super::super::certify::{certify, Target};
use super::constraints::Source;
use super::{compact, quality, remesh_source, tris_of, RemeshOptions, Remeshing};
use crate::measure::{path_length, polygon_area, Measures};
use crate::network::embedding::Embedding;

/// A written result's polygons and curves (every index checked by the
/// caller against `points`).
pub struct Written<'a> {
    /// Vertex positions.
    pub points: &'a [[f64; 3]],
    /// Polygon `f` is `face_verts[face_start[f]..face_start[f + 1]]`.
    pub face_start: &'a [u32],
    /// See `face_start`.
    pub face_verts: &'a [u32],
    /// Per polygon its patch (below `patches`).
    pub face_patch: &'a [u32],
    /// Per polygon the cells on its positive and negative side
    /// (`u32::MAX`: none); the same for every polygon of a patch.
    pub face_cells: &'a [[u32; 2]],
    /// Per polygon its two labels; the same for every polygon of a patch.
    pub face_label: &'a [[i32; 2]],
    /// Number of patches.
    pub patches: usize,
    /// Number of cells.
    pub cells: usize,
    /// Chains as vertex paths (a closed chain repeats its first vertex).
    pub chains: &'a [Vec<u32>],
    /// Corner vertices.
    pub corners: &'a [u32],
    /// Per cell its volume as written (empty: not measured).
    pub cell_volume: &'a [f64],
}

/// The remeshed result: triangles, each with its patch's cells and labels;
/// chains and corners as paths and points of the new vertices.
#[derive(Clone, Debug)]
pub struct Rewritten {
    /// Vertex positions.
    pub points: Vec<[f64; 3]>,
    /// Triangle `t` is `face_verts[3t..3t + 3]` (`face_start[t] = 3t`).
    pub face_start: Vec<u32>,
    /// See `face_start`.
    pub face_verts: Vec<u32>,
    /// Per triangle its patch.
    pub face_patch: Vec<u32>,
    /// Per triangle its patch's cells.
    pub face_cells: Vec<[u32; 2]>,
    /// Per triangle its patch's labels.
    pub face_label: Vec<[i32; 2]>,
    /// The chains as paths of the new edges (same ends).
    pub chains: Vec<Vec<u32>>,
    /// The corners (same points).
    pub corners: Vec<u32>,
    /// Patch areas and chain lengths of the triangles; cell volumes (when
    /// written before) moved by the change of their polygons (see
    /// [`remesh_written`]).
    pub measures: Measures,
    /// What remeshing did; `refused > 0`: everything above is the input as
    /// written (never worse than without remeshing).
    pub report: Remeshing,
    /// The certificate of the remeshed triangles (`None` when refused).
    pub embedding: Option<Embedding>,
}

/// The grid's box as far as the polygons show it: the bounding box of the
/// vertices of *free border* edges (held by one polygon and on no chain:
/// a patch's border on the box, the only place a patch ends without a
/// chain), `None` when there are none. (The bounding box of all vertices
/// would be wrong for a result that does not reach the box: a curve on its
/// extreme, e.g. the square's border of `sphere-plane-hole`, would be taken
/// for a side of the box, and its vertices, whose doubles are not all the
/// same there, would split it into many constraint kinds.)
fn used_box(w: &Written) -> Option<[[f64; 3]; 2]> {
    let mut uses: rustc_hash::FxHashMap<(u32, u32), u32> = rustc_hash::FxHashMap::default();
    for f in 0..w.face_start.len() - 1 {
        let l = &w.face_verts[w.face_start[f] as usize..w.face_start[f + 1] as usize];
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            *uses.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    for c in w.chains {
        for e in c.windows(2) {
            uses.remove(&(e[0].min(e[1]), e[0].max(e[1])));
        }
    }
    let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for (&(u, v), _) in uses.iter().filter(|(_, &n)| n == 1) {
        for p in [w.points[u as usize], w.points[v as usize]] {
            for k in 0..3 {
                b[0][k] = b[0][k].min(p[k]);
                b[1][k] = b[1][k].max(p[k]);
            }
        }
    }
    (b[0][0] <= b[1][0]).then_some(b)
}

/// Every index in range (the error names the array and the element).
fn check_indices(w: &Written) -> Result<(), String> {
    let np = w.points.len() as u32;
    if w.face_start.first() != Some(&0) || *w.face_start.last().unwrap() as usize != w.face_verts.len() {
        return Err("offsets: must start at 0 and end at the length of indices".into());
    }
    if let Some(f) = w.face_start.windows(2).position(|s| s[1] < s[0] + 3) {
        return Err(format!("face {f}: fewer than 3 vertices (or offsets not increasing)"));
    }
    if let Some(i) = w.face_verts.iter().position(|&v| v >= np) {
        return Err(format!("indices[{i}]: vertex {} does not exist ({np} points)", w.face_verts[i]));
    }
    if let Some(c) = w.chains.iter().position(|c| c.iter().any(|&v| v >= np)) {
        return Err(format!("chain {c}: refers to a vertex that does not exist ({np} points)"));
    }
    if let Some(i) = w.corners.iter().position(|&v| v >= np) {
        return Err(format!("corners[{i}]: vertex {} does not exist ({np} points)", w.corners[i]));
    }
    if let Some(f) = w.face_cells.iter().position(|c| c.iter().any(|&x| x != u32::MAX && x as usize >= w.cells)) {
        return Err(format!("face {f}: cells {:?}: a cell that does not exist ({} cells)", w.face_cells[f], w.cells));
    }
    if !w.points.iter().all(|p| p.iter().all(|x| x.is_finite())) {
        return Err("points: a coordinate is not finite".into());
    }
    Ok(())
}

/// Per patch, its cells and labels: the same for all its polygons, or an
/// error naming the patch (not a septa result).
fn per_patch(w: &Written) -> Result<Vec<([u32; 2], [i32; 2])>, String> {
    let mut out: Vec<Option<([u32; 2], [i32; 2])>> = vec![None; w.patches];
    for f in 0..w.face_patch.len() {
        let p = w.face_patch[f] as usize;
        let this = (w.face_cells[f], w.face_label[f]);
        let slot =
            out.get_mut(p).ok_or_else(|| format!("face {f}: patch {p} does not exist ({} patches)", w.patches))?;
        match slot {
            None => *slot = Some(this),
            Some(s) if *s != this => {
                return Err(format!(
                    "patch {p}: its polygons have different cells or labels ({:?} and {:?} at face {f}): not one patch \
                     of a septa result",
                    s, this
                ))
            }
            Some(_) => {}
        }
    }
    Ok(out.into_iter().map(|s| s.unwrap_or(([u32::MAX; 2], [-1, -1]))).collect())
}

/// Six times the signed volume of the cone from `o` over a polygon's fan.
fn cone6(x: &[[f64; 3]], poly: &[u32], o: [f64; 3]) -> f64 {
    let d = |v: u32| {
        let p = x[v as usize];
        [p[0] - o[0], p[1] - o[1], p[2] - o[2]]
    };
    let p0 = d(poly[0]);
    let mut s = 0.0;
    for k in 1..poly.len() - 1 {
        let (a, b) = (d(poly[k]), d(poly[k + 1]));
        let c = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        s += p0[0] * c[0] + p0[1] * c[1] + p0[2] * c[2];
    }
    s
}

/// Per cell, the cone volumes from `o` over its polygons (the normal, counter-
/// clockwise from the positive side, points into the positive side's cell:
/// `measure::cell_volumes`' convention).
fn cell_cones(x: &[[f64; 3]], start: &[u32], verts: &[u32], cells: &[[u32; 2]], n: usize, o: [f64; 3]) -> Vec<f64> {
    let mut six = vec![0.0; n];
    for f in 0..start.len() - 1 {
        let v = cone6(x, &verts[start[f] as usize..start[f + 1] as usize], o);
        let [cp, cn] = cells[f];
        if let Some(s) = six.get_mut(cn as usize) {
            *s += v;
        }
        if let Some(s) = six.get_mut(cp as usize) {
            *s -= v;
        }
    }
    six.iter().map(|s| s / 6.0).collect()
}

/// Remeshes a written result (module doc). The cell volumes written before
/// are moved by the change of the cones over their polygons from the box's
/// first corner: exact for a cell the network closes; for a cell reaching
/// the box, its footprint on the box's far sides is taken as before (the
/// border's resampling changes it by slivers of width under the Hausdorff
/// distance).
pub fn remesh_written(w: &Written, opts: &RemeshOptions) -> Result<Rewritten, String> {
    let nf = w.face_patch.len();
    if w.face_start.len() != nf + 1 || w.face_cells.len() != nf || w.face_label.len() != nf {
        return Err(format!(
            "remesh: {nf} faces but {} offsets, {} cells rows, {} label rows",
            w.face_start.len(),
            w.face_cells.len(),
            w.face_label.len()
        ));
    }
    check_indices(w)?;
    let patch_of = per_patch(w)?;
    let bounds = used_box(w);
    let src = Source {
        points: w.points,
        start: w.face_start,
        verts: w.face_verts,
        patch: w.face_patch,
        chains: w.chains,
        corners: w.corners,
        bounds,
    };
    let r = remesh_source(&src, opts, w.patches, None)?;
    let map = compact(&r.soup);
    let n = map.iter().filter(|&&m| m != u32::MAX).count();
    let mut points = vec![[0.0; 3]; n];
    for (v, &m) in map.iter().enumerate() {
        if m != u32::MAX {
            points[m as usize] = r.soup.x[v];
        }
    }
    let m = |v: u32| map[v as usize];
    let mut out = Rewritten {
        points,
        face_start: (0..=r.tris.len() as u32).map(|i| 3 * i).collect(),
        face_verts: r.tris.iter().flat_map(|t| t.map(m)).collect(),
        face_patch: r.tri_patch.clone(),
        face_cells: r.tri_patch.iter().map(|&p| patch_of[p as usize].0).collect(),
        face_label: r.tri_patch.iter().map(|&p| patch_of[p as usize].1).collect(),
        chains: r.chains.iter().map(|c| c.iter().map(|&v| m(v)).collect()).collect(),
        corners: w.corners.iter().map(|&v| m(v)).collect(),
        measures: Measures::default(),
        report: r.report,
        embedding: None,
    };
    let mut t = Target {
        points: &mut out.points,
        start: &out.face_start,
        verts: &mut out.face_verts,
        cells: Some(&out.face_cells),
        bounds,
        fixed: None,
    };
    let e = certify(&mut t);
    if e.after.violations() > 0 {
        // never worse: the input as written
        out.report.refused = e.after.violations();
        out.report.after = out.report.before.clone();
        out.points = w.points.to_vec();
        out.face_start = w.face_start.to_vec();
        out.face_verts = w.face_verts.to_vec();
        out.face_patch = w.face_patch.to_vec();
        out.face_cells = w.face_cells.to_vec();
        out.face_label = w.face_label.to_vec();
        out.chains = w.chains.to_vec();
        out.corners = w.corners.to_vec();
    } else {
        out.report.after = quality::quality(&out.points, &tris_of(&out.face_verts));
        out.embedding = Some(e);
    }
    let mut patch_area = vec![0.0; w.patches];
    for f in 0..out.face_patch.len() {
        let poly = &out.face_verts[out.face_start[f] as usize..out.face_start[f + 1] as usize];
        patch_area[out.face_patch[f] as usize] += polygon_area(&out.points, poly);
    }
    // the apex on the box's near sides, where a footprint's change adds nothing
    let apex = bounds.map(|b| b[0]).or_else(|| w.face_verts.first().map(|&v| w.points[v as usize]));
    let cell_volume = match (w.cell_volume.len() == w.cells, apex) {
        (true, Some(o)) if w.cells > 0 => {
            let before = cell_cones(w.points, w.face_start, w.face_verts, w.face_cells, w.cells, o);
            let after = cell_cones(&out.points, &out.face_start, &out.face_verts, &out.face_cells, w.cells, o);
            (0..w.cells).map(|c| w.cell_volume[c] + (after[c] - before[c])).collect()
        }
        _ => Vec::new(),
    };
    out.measures = Measures {
        cell_volume,
        patch_area,
        chain_length: out.chains.iter().map(|c| path_length(&out.points, c)).collect(),
    };
    Ok(out)
}
