//! Exact check of a written polyhedral mesh (the floating-point embedding of
//! TopoCut Sec. 6.1 made a guarantee instead of a heuristic): on the very
//! doubles that were written, every cell is a closed, consistently oriented,
//! non-self-intersecting polyhedron of positive volume with planar faces.
//!
//! The check knows nothing of how the mesh was made: it takes points and
//! cells as lists of outward polygons (what `cells.vtu` holds), so it also
//! verifies any polyhedral `.vtu` (`septa cut --verify FILE.vtu`). Every
//! decision is an exact sign on the doubles (`selfx` orientations, exact
//! volume sums); nothing is decided by a tolerance.
//!
//! What is checked:
//! 1. each polygon has at least 3 distinct vertices, not all collinear;
//! 2. planarity: every vertex of a polygon lies exactly on the plane of
//!    its first non-collinear corner triple (orient3d = 0);
//! 3. closed and consistently oriented: in each cell every undirected edge
//!    is used as often in one direction as in the other;
//! 4. no two distinct vertex ids at the same point;
//! 5. no self-intersection: each distinct face (shared faces once) is cut
//!    into triangles without new vertices, and no two triangles of the whole
//!    mesh meet except in shared vertices and edges (exact, `selfx`); this
//!    covers the faces of one cell and also cells overlapping each other;
//! 6. positive volume: the exact sign of `sum det(b - o, c - o, d - o)`
//!    over each cell's triangles (divergence theorem);
//! 7. every vertex in use has finite coordinates (with an infinite or NaN
//!    one nothing above would be a proof, and nothing above is checked).
//!
//! Item 5 uses a floating-point ear clipping to triangulate planar polygons;
//! a poor triangulation of a valid polygon can only add reported
//! intersections, never hide one, so a zero report is a proof. When nothing
//! else is wrong, item 5 is first tried through the cells' shapes
//! ([`crate::cut::check::tiling`]: cells star-shaped around a point, proven by exact
//! orientations, need no pair test among their own triangles, and cells that
//! are embedded and share their faces consistently cannot overlap); only
//! when that certificate does not hold are all pairs tested, so the report
//! is the same either way.

use crate::cut::check::cell_polygons::CellPolygons;
use crate::cut::check::polygon::{collinear, newell, polygon_planar};
use crate::cut::check::tiling::{tiling_plan, TilingPlan};
use crate::cut::check::verify_volume::volume_sign;
use crate::cut::triangles::plane_separation::PlaneSeparation;
use crate::cut::triangles::radix::sort_u64;
use crate::cut::triangles::selfx::{intersecting_pairs_touching, intersecting_pairs_wanted};
use crate::cut::triangles::triangulate::triangulate;
use rustc_hash::FxHashMap;
use septa_exact::Sign;

/// What [`verify_cells`] found; every count is exact. `examples` names the
/// first few offending elements.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct VerifyReport {
    /// Cells checked.
    pub cells: usize,
    /// Distinct faces (a face shared by two cells counts once).
    pub faces: usize,
    /// Triangles the distinct faces were cut into for the intersection test.
    pub triangles: usize,
    /// Polygons with fewer than 3 distinct vertices or all corners collinear.
    pub degenerate_faces: usize,
    /// Polygons whose vertices are not exactly coplanar.
    pub nonplanar_faces: usize,
    /// (cell, undirected edge) pairs used unequally in the two directions:
    /// the cell is not closed or not consistently oriented there.
    pub unbalanced_edges: usize,
    /// Pairs of distinct vertex ids at the same point.
    pub coincident_points: usize,
    /// Triangles of the face triangulation with collinear corners.
    pub degenerate_triangles: usize,
    /// Pairs of triangles meeting away from shared vertices and edges.
    pub intersecting_pairs: usize,
    /// Cells whose exact volume is zero or negative.
    pub nonpositive_cells: usize,
    /// Vertices in use with an infinite or NaN coordinate (nothing else is
    /// checked of a mesh that has one; written only when not zero).
    #[serde(skip_serializing_if = "is_zero")]
    pub nonfinite_points: usize,
    /// The first offending elements, in words.
    pub examples: Vec<String>,
    /// The polygons (vertex loops, as written in some cell) that are
    /// non-planar, degenerate, or hold an offending triangle: what a repair
    /// would re-triangulate.
    #[serde(skip)]
    pub offending_polygons: Vec<Vec<u32>>,
    /// The triangles tested and the intersecting pairs found, by vertex
    /// ids, for a re-check of a changed mesh ([`verify_cells_since`]).
    #[serde(skip)]
    pub(crate) memo: Option<std::sync::Arc<PairMemo>>,
    /// Were the pairs proven apart by the cells' shapes ([`tiling`])
    /// rather than pair by pair? (The report is the same either way.)
    #[serde(skip)]
    pub(crate) tiled: bool,
}

/// What the triangle-triangle test of one check saw: its triangles (each
/// as its sorted vertex ids) and its intersecting pairs.
#[derive(Debug, Default)]
pub(crate) struct PairMemo {
    pub(crate) triangles: rustc_hash::FxHashSet<[u32; 3]>,
    pairs: Vec<([u32; 3], [u32; 3])>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

fn tri_key(t: &[u32; 3]) -> [u32; 3] {
    let mut k = *t;
    k.sort_unstable();
    k
}

impl VerifyReport {
    /// Total number of violations (0: every cell is proven valid).
    pub fn violations(&self) -> usize {
        self.degenerate_faces
            + self.nonplanar_faces
            + self.unbalanced_edges
            + self.coincident_points
            + self.degenerate_triangles
            + self.intersecting_pairs
            + self.nonpositive_cells
            + self.nonfinite_points
    }

    fn note(&mut self, s: impl FnOnce() -> String) {
        if self.examples.len() < 10 {
            self.examples.push(s());
        }
    }
}

/// The rotation of a loop starting at its smallest vertex, read in the
/// direction whose second vertex is smaller: the same key for a face seen
/// from either of its cells; `true` when it had to be reversed.
/// The key is written into `key` (a buffer reused across faces: most faces
/// are met twice, and the second time the key is only looked up).
fn face_key(poly: &[u32], key: &mut Vec<u32>) -> bool {
    let n = poly.len();
    let m = (0..n).min_by_key(|&i| poly[i]).unwrap_or(0);
    key.clear();
    if n > 1 && poly[(m + n - 1) % n] < poly[(m + 1) % n] {
        key.extend((0..n).map(|i| poly[(m + n - i) % n]));
        true
    } else {
        key.extend((0..n).map(|i| poly[(m + i) % n]));
        false
    }
}

/// A report standing for an earlier exact check that found no two of
/// `triangles` (vertex ids into the mesh about to be checked) meeting: passed
/// as `prev` to [`verify_cells_since`], it spares the pairs of two of them.
/// The cut's input check ([`crate::cut::triangles::selfx::check_self_intersections`]) proves
/// this of the input triangles, and an input triangle no plane crosses is
/// written unchanged (its corners are never moved): on a large mesh most of
/// the written triangles, whose pairs the check would otherwise test twice.
pub(crate) fn proven_disjoint(triangles: impl IntoIterator<Item = [u32; 3]>) -> VerifyReport {
    let triangles = triangles.into_iter().map(|t| tri_key(&t)).collect();
    let memo = PairMemo { triangles, pairs: Vec::new() };
    VerifyReport { memo: Some(std::sync::Arc::new(memo)), ..Default::default() }
}

/// Checks `cells` (each a list of polygons of vertex ids into `x`, oriented
/// outwards) exactly on the doubles `x`; see the module doc for what.
pub fn verify_cells(x: &[[f64; 3]], cells: &[Vec<Vec<u32>>]) -> VerifyReport {
    verify_cells_since(x, cells, None)
}

/// [`verify_cells`] after a change to a mesh that `prev` checked, where no
/// vertex id `prev` saw has moved (new vertices may have been appended):
/// the same report, but only pairs of triangles with at least one triangle
/// that `prev` did not test go through the intersection test; the pairs of
/// triangles tested before are taken from `prev` (whether two triangles
/// meet depends only on their corners' coordinates). The repair re-writes a
/// few faces and re-checks: this re-check used to test every pair again.
pub fn verify_cells_since(x: &[[f64; 3]], cells: &[Vec<Vec<u32>>], prev: Option<&VerifyReport>) -> VerifyReport {
    verify_flat(x, &CellPolygons::from_nested(cells), prev, &[])
}

fn key_hash(k: &[u32]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = rustc_hash::FxHasher::default();
    k.hash(&mut h);
    h.finish()
}

/// The distinct faces met so far, each by its key ([`face_key`]) in one
/// arena, found by the key's hash (keys of equal hash beyond the first kept
/// in `collided`): no vector per face.
#[derive(Default)]
struct FaceIndex {
    by_hash: FxHashMap<u64, u32>,
    collided: FxHashMap<Vec<u32>, u32>,
    key_start: Vec<u32>,
    keys: Vec<u32>,
}

impl FaceIndex {
    fn key(&self, f: u32) -> &[u32] {
        &self.keys[self.key_start[f as usize] as usize..self.key_start[f as usize + 1] as usize]
    }

    fn get(&self, key: &[u32], h: u64) -> Option<u32> {
        match self.by_hash.get(&h) {
            Some(&f) if self.key(f) == key => Some(f),
            Some(_) => self.collided.get(key).copied(),
            None => None,
        }
    }

    /// Records `key` as face `f` (the next id).
    fn insert(&mut self, key: &[u32], h: u64, f: u32) {
        if self.key_start.is_empty() {
            self.key_start.push(0);
        }
        self.keys.extend_from_slice(key);
        self.key_start.push(self.keys.len() as u32);
        if self.by_hash.contains_key(&h) {
            self.collided.insert(key.to_vec(), f);
        } else {
            self.by_hash.insert(h, f);
        }
    }
}

/// Counts the undirected edges of one cell used unequally in the two
/// directions, calling `bad(a, b)` for each in increasing order: `fwd` and
/// `bwd` hold the cell's edges `(min << 32) | max` as used from the smaller
/// vertex and from the larger (sorted here). Equal multisets: balanced.
fn unbalanced(fwd: &mut Vec<u64>, bwd: &mut Vec<u64>, mut bad: impl FnMut(u32, u32)) -> usize {
    sort_u64(fwd);
    sort_u64(bwd);
    let (mut i, mut j, mut n) = (0, 0, 0);
    while i < fwd.len() || j < bwd.len() {
        let k = match (fwd.get(i), bwd.get(j)) {
            (Some(&a), Some(&b)) => a.min(b),
            (Some(&a), None) => a,
            (None, Some(&b)) => b,
            (None, None) => unreachable!(),
        };
        let (mut bal, i0, j0) = (0i64, i, j);
        while fwd.get(i) == Some(&k) {
            i += 1;
        }
        while bwd.get(j) == Some(&k) {
            j += 1;
        }
        bal += (i - i0) as i64 - (j - j0) as i64;
        if bal != 0 {
            n += 1;
            bad((k >> 32) as u32, k as u32);
        }
    }
    n
}

/// [`verify_cells_since`] on cells in their flat form. `planes` (`[a, b,
/// c, d]`, e.g. the cutting planes) only speed up the intersection test
/// ([`PlaneSeparation`]): any planes, or none, give the same report.
pub(crate) fn verify_flat(
    x: &[[f64; 3]],
    cells: &CellPolygons,
    prev: Option<&VerifyReport>,
    planes: &[[f64; 4]],
) -> VerifyReport {
    verify_flat_with(x, cells, prev, planes, true)
}

/// [`verify_flat`], trying the certificate of [`tiling`] first when
/// `use_tiling` (the tests compare it with every pair tested).
pub(crate) fn verify_flat_with(
    x: &[[f64; 3]],
    cells: &CellPolygons,
    prev: Option<&VerifyReport>,
    planes: &[[f64; 4]],
    use_tiling: bool,
) -> VerifyReport {
    let nc = cells.num_cells();
    let mut r = VerifyReport { cells: nc, ..Default::default() };
    // every decision below is an exact sign on finite doubles; the vertices
    // in use are looked at only when some point is not finite
    if !x.iter().flatten().all(|c| c.is_finite()) {
        let mut seen = vec![false; x.len()];
        for &v in &cells.verts {
            match x.get(v as usize) {
                Some(p) if !seen[v as usize] && !p.iter().all(|c| c.is_finite()) => {
                    seen[v as usize] = true;
                    r.nonfinite_points += 1;
                    r.note(|| format!("vertex {v} has a non-finite coordinate {p:?}"));
                }
                _ => {}
            }
        }
        if r.nonfinite_points > 0 {
            // nothing else is checked: the exact signs are of finite doubles
            return r;
        }
    }
    // distinct faces, triangulated once; each cell refers to them with a direction
    let mut index = FaceIndex::default();
    let mut tri_start: Vec<u32> = vec![0];
    let mut face_tris: Vec<[u32; 3]> = Vec::new();
    let mut bad_faces: Vec<u32> = Vec::new();
    let mut ref_start: Vec<u32> = Vec::with_capacity(nc + 1);
    ref_start.push(0);
    let mut refs: Vec<(u32, bool)> = Vec::with_capacity(cells.poly_start.len());
    let (mut key, mut distinct) = (Vec::new(), Vec::new());
    let (mut fwd, mut bwd): (Vec<u64>, Vec<u64>) = (Vec::new(), Vec::new());
    for ci in 0..nc {
        for (fi, poly) in cells.cell(ci).enumerate() {
            let rev = face_key(poly, &mut key);
            let h = key_hash(&key);
            let id = match index.get(&key, h) {
                Some(id) => id,
                None => {
                    let id = tri_start.len() as u32 - 1;
                    distinct.clear();
                    distinct.extend_from_slice(poly);
                    distinct.sort_unstable();
                    distinct.dedup();
                    let planar = match polygon_planar(x, &key) {
                        _ if distinct.len() != key.len() => None,
                        p => p,
                    };
                    match planar {
                        Some(planar) => {
                            if !planar {
                                bad_faces.push(id);
                                r.nonplanar_faces += 1;
                                r.note(|| format!("face {fi} of cell {ci} is not planar"));
                            }
                            if key.len() == 3 {
                                face_tris.push([key[0], key[1], key[2]]);
                            } else {
                                face_tris.extend(triangulate(x, std::slice::from_ref(&key), newell(x, &key)));
                            }
                        }
                        None => {
                            bad_faces.push(id);
                            r.degenerate_faces += 1;
                            r.note(|| format!("face {fi} of cell {ci} is degenerate ({} vertices)", poly.len()));
                        }
                    }
                    tri_start.push(face_tris.len() as u32);
                    index.insert(&key, h, id);
                    id
                }
            };
            refs.push((id, rev));
        }
        ref_start.push(refs.len() as u32);
        // closed and consistently oriented: each undirected edge as often both ways
        fwd.clear();
        bwd.clear();
        for poly in cells.cell(ci) {
            for i in 0..poly.len() {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                let k = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                if a < b {
                    fwd.push(k);
                } else {
                    bwd.push(k);
                }
            }
        }
        // the first few named, as `note` would keep them
        let room = 10usize.saturating_sub(r.examples.len());
        let mut bad = Vec::new();
        r.unbalanced_edges += unbalanced(&mut fwd, &mut bwd, |a, b| {
            if bad.len() < room {
                bad.push((a, b));
            }
        });
        for (a, b) in bad {
            r.note(|| format!("cell {ci} is not closed or not consistently oriented at edge {a}-{b}"));
        }
    }
    let nf = tri_start.len() - 1;
    let tris_of = |f: usize| &face_tris[tri_start[f] as usize..tri_start[f + 1] as usize];
    r.faces = nf;
    // coincident points among the vertices in use (ascending ids from a
    // mark per vertex, no sort)
    let mut in_use = vec![false; x.len()];
    for &v in face_tris.iter().flatten() {
        in_use[v as usize] = true;
    }
    let used = (0..x.len() as u32).filter(|&v| in_use[v as usize]);
    // +0.0 and -0.0 are the same point
    let bits = |v: u32| x[v as usize].map(|c| (c + 0.0).to_bits());
    // nearly always none: a set of positions proves it without sorting
    // them; the sort below names the pairs in a fixed order when some exist
    let mut seen: rustc_hash::FxHashSet<[u64; 3]> = Default::default();
    seen.reserve(used.clone().count());
    if !used.clone().all(|v| seen.insert(bits(v))) {
        let mut by_pos: Vec<([u64; 3], u32)> = used.map(|v| (bits(v), v)).collect();
        by_pos.sort_unstable();
        for w in by_pos.windows(2) {
            if w[0].0 == w[1].0 {
                r.coincident_points += 1;
                let (a, b) = (w[0].1, w[1].1);
                r.note(|| format!("vertices {a} and {b} are at the same point"));
            }
        }
    }
    drop((seen, in_use));
    // every triangle once; degenerate ones reported and kept out of the pair test
    let mut all: Vec<[u32; 3]> = Vec::with_capacity(face_tris.len());
    let mut tri_face: Vec<u32> = Vec::with_capacity(face_tris.len());
    for f in 0..nf {
        for t in tris_of(f) {
            if collinear(x, t[0], t[1], t[2]) {
                bad_faces.push(f as u32);
                r.degenerate_triangles += 1;
                r.note(|| format!("face {f} has a triangle with collinear corners {t:?}"));
            } else {
                all.push(*t);
                tri_face.push(f as u32);
            }
        }
    }
    r.triangles = all.len() + r.degenerate_triangles;
    // exact volume sign per cell (reported after the pairs)
    let mut tris: Vec<[u32; 3]> = Vec::new();
    let positive: Vec<bool> = (0..nc)
        .map(|ci| {
            tris.clear();
            for &(f, rev) in &refs[ref_start[ci] as usize..ref_start[ci + 1] as usize] {
                for t in tris_of(f as usize) {
                    tris.push(if rev { [t[0], t[2], t[1]] } else { *t });
                }
            }
            volume_sign(x, &tris) == Sign::Positive
        })
        .collect();
    // the cells' shapes prove most pairs apart when nothing else is wrong
    // (`tiling`; with no degenerate triangle, `all` is `face_tris`)
    let memo = prev.and_then(|p| p.memo.as_deref());
    let plan = (use_tiling && r.violations() == r.nonplanar_faces && positive.iter().all(|&p| p))
        .then(|| tiling_plan(x, &face_tris, &tri_start, &refs, &ref_start))
        .flatten();
    if std::env::var_os("SEPTA_DEBUG").is_some() {
        match &plan {
            Some(p) => eprintln!(
                "verify: tiling plan: {} of {} cells star-shaped, {} outer triangles of {}",
                p.star_cells(),
                nc,
                p.outer.len(),
                all.len()
            ),
            None => eprintln!("verify: no tiling plan"),
        }
    }
    let separation = PlaneSeparation::new(x, &all, planes);
    let pairs = match plan {
        Some(plan) if tiling_certified(x, &all, &plan, memo, separation.as_ref()) => {
            r.tiled = true;
            Vec::new()
        }
        _ => triangle_pairs(x, &all, memo, separation.as_ref()),
    };
    r.intersecting_pairs = pairs.len();
    bad_faces.extend(pairs.iter().flat_map(|&(a, b)| [tri_face[a as usize], tri_face[b as usize]]));
    for &(a, b) in pairs.iter().take(3) {
        let (ta, tb) = (all[a as usize], all[b as usize]);
        r.note(|| format!("triangles {ta:?} and {tb:?} intersect"));
    }
    for ci in (0..nc).filter(|&ci| !positive[ci]) {
        r.nonpositive_cells += 1;
        r.note(|| format!("cell {ci} has no positive volume"));
    }
    // a re-check follows only a report with violations
    if r.violations() > 0 {
        r.memo = pair_memo(&all, &pairs);
    }
    bad_faces.sort_unstable();
    bad_faces.dedup();
    r.offending_polygons = bad_faces.iter().map(|&f| index.key(f).to_vec()).collect();
    r
}

/// Does the pair test leave the certificate of `plan` standing ([`tiling`]:
/// no two of its wanted triangles meet)? Pairs of two triangles that an
/// earlier check found no pair among (`prev`) are known; `separation`
/// holds the plane bits of `all`.
fn tiling_certified(
    x: &[[f64; 3]],
    all: &[[u32; 3]],
    plan: &TilingPlan,
    prev: Option<&PairMemo>,
    separation: Option<&PlaneSeparation>,
) -> bool {
    let pick = |idx: &[u32]| -> (Vec<[u32; 3]>, Option<PlaneSeparation>) {
        (idx.iter().map(|&t| all[t as usize]).collect(), separation.map(|s| s.subset(idx)))
    };
    // the outer surface, across cells
    let (outer, sep) = pick(&plan.outer);
    let fresh: Option<Vec<bool>> =
        prev.filter(|m| m.pairs.is_empty()).map(|m| outer.iter().map(|t| !m.triangles.contains(&tri_key(t))).collect());
    let wanted = |a: usize, b: usize| plan.outer_wanted(a, b);
    if !intersecting_pairs_wanted(x, &outer, fresh.as_deref(), sep.as_ref(), true, &wanted).is_empty() {
        return false;
    }
    // inside each cell that is not star-shaped, the pairs with a triangle
    // inside (`fresh`)
    plan.open.iter().all(|(idx, inside)| {
        let (tris, sep) = pick(idx);
        intersecting_pairs_touching(x, &tris, Some(inside), sep.as_ref(), true).is_empty()
    })
}

/// The intersecting pairs of `all` (indices, sorted), through the memo of a
/// previous check when there is one (not with a triangle written twice:
/// pairs are named by vertex ids).
fn triangle_pairs(
    x: &[[f64; 3]],
    all: &[[u32; 3]],
    prev: Option<&PairMemo>,
    separation: Option<&PlaneSeparation>,
) -> Vec<(u32, u32)> {
    let every = || intersecting_pairs_touching(x, all, None, separation, false);
    let Some(m) = prev else { return every() };
    let keys: Vec<[u32; 3]> = all.iter().map(tri_key).collect();
    let index: FxHashMap<[u32; 3], u32> = keys.iter().enumerate().map(|(i, k)| (*k, i as u32)).collect();
    if index.len() != keys.len() {
        return every();
    }
    let fresh: Vec<bool> = keys.iter().map(|k| !m.triangles.contains(k)).collect();
    let mut pairs = intersecting_pairs_touching(x, all, Some(&fresh), separation, false);
    for (a, b) in &m.pairs {
        if let (Some(&i), Some(&j)) = (index.get(a), index.get(b)) {
            pairs.push((i.min(j), i.max(j)));
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// The memo of a check of `all` that found `pairs` (indices into `all`),
/// for a re-check; none when a triangle is written twice. Made only for a
/// report with violations (on a clean one it cost a hash set of every
/// triangle: a re-check follows only a report with violations).
fn pair_memo(all: &[[u32; 3]], pairs: &[(u32, u32)]) -> Option<std::sync::Arc<PairMemo>> {
    let keys: Vec<[u32; 3]> = all.iter().map(tri_key).collect();
    let triangles: rustc_hash::FxHashSet<[u32; 3]> = keys.iter().copied().collect();
    (triangles.len() == keys.len()).then(|| {
        let pairs = pairs.iter().map(|&(a, b)| (keys[a as usize], keys[b as usize])).collect();
        std::sync::Arc::new(PairMemo { triangles, pairs })
    })
}

#[cfg(test)]
#[path = "verify_tests.rs"]
mod tests;
