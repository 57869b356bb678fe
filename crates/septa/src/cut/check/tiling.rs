//! A certificate that the written cells tile their domain without two
//! triangles meeting improperly, which needs far fewer exact pair tests than
//! testing every pair of triangles whose boxes overlap ([`crate::cut::check::verify`],
//! item 5).
//!
//! Most triangles of a cut-cell mesh lie on the cutting planes, between two
//! cells that are convex, or nearly so, in the exact arrangement. A cell
//! whose surface is star-shaped around a point is embedded, and that is
//! decided from its own triangles, with a few orientations each. If every
//! cell is embedded and so is the mesh's outer surface, the cells cannot
//! overlap, and then no two triangles can meet improperly at all: only the
//! outer surface's pairs and those inside cells that are not star-shaped go
//! through the pair test.
//!
//! # The proof
//!
//! Write `S_c` for the oriented triangles of cell `c` and `S_b` for those of
//! the faces used by one cell only (the outer surface). The certificate
//! holds when
//! 1. every face is used by one cell, or by two with opposite orientations;
//! 2. every `S_c` and `S_b` is a closed, connected 2-manifold (each edge in
//!    exactly two of its triangles, once in each direction; each vertex's
//!    triangles one fan), [`Surface::new`], [`Surface::connected_manifold`];
//! 3. every `S_c` is embedded: star-shaped ([`Surface::star_shaped`]) or no two of
//!    its triangles meeting improperly (exact pair test), and `S_b` is
//!    embedded (two of its triangles in one cell by that cell's
//!    embedding, in different cells by the exact pair test);
//! 4. every cell has positive exact volume, no two vertex ids share a
//!    point and no triangle is degenerate (checked by the caller).
//!
//! Then, with `w_X` the winding number of surface `X`: by 2 and 3 each
//! `S_c` is a connected embedded closed surface, so (Jordan-Brouwer)
//! `w_c` is 1 on one side and 0 on the other, 1 inside by 4; likewise
//! `w_b` is 0 or 1 (its volume is the sum of the cells'). By 1 the
//! chains add up: `sum_c S_c = S_b`, so `sum_c w_c = w_b <= 1` and the
//! cells' interiors are pairwise disjoint. Now let `y` be a point where two
//! triangles meet outside their shared vertices and edges.
//! - If `y` is inside a triangle `t` of a face between cells `A` and `B`:
//!   near `y`, `S_A` and `S_B` are `t` alone (both embedded), so `A` holds
//!   the half-ball on one side of `t` and `B` the other; no other cell
//!   reaches `y`, so the other triangle is of `A` or `B`, which are
//!   embedded: a contradiction. If `t` is on the outer surface, `S_b`
//!   embedded gives `w_b = 0` on its outer side and the same follows.
//! - If `y` is inside an edge `e`: near `y`, each cell whose surface holds
//!   `e` is the wedge between its two triangles at `e` (by 2 and 3), and
//!   every other cell has a constant winding number. Crossing a triangle of
//!   an interior face at `e` swaps one wedge for another, so the wedges'
//!   count changes only across the outer surface's triangles at `e` (none,
//!   or two, where `w_b` steps between 1 and 0): it is 1 where `w_b` is 1
//!   and 0 where it is 0, and every other cell's winding number near `y` is
//!   0. So no cell reaches `y` without holding `e`, and every triangle
//!   through `y` has the edge `e`: a contradiction.
//! - If `y` is a vertex of both: two ids at one point, excluded by 4.
//!
//! # Star-shaped, exactly
//!
//! `S` is star-shaped around `q` when (a) `q` lies strictly on the inner
//! side of every triangle's plane and (b) around every vertex `v` the
//! triangles' other corners, seen along the axis from `q` through `v`,
//! turn once around it, not several times (a branched fan). Then the central
//! projection from `q` onto a sphere is a local homeomorphism everywhere
//! (inside triangles by (a); across an edge the two triangles lie on
//! opposite sides of the plane through `q` and the edge, by (a) and the
//! edge being used both ways; at vertices by (b)), so a covering of the
//! sphere by the connected `S`, hence one-to-one: `S` is embedded.
//! (b) is decided by orientations only: with the fan `a_1 .. a_k` around
//! `v`, every step `a_i -> a_(i+1)` turns by less than half a turn (it is a
//! triangle facing `q`), so the fan turns once exactly when the signs of
//! `orient(q, v, a_1, a_i)`, `i = 2..k`, run `+ .. + [0] - .. -`.

use crate::cut::triangles::orient::orient;
use crate::cut::triangles::radix::radix_sort_keys;
use crate::scene::vec3::{cross, dot, norm, scale, sub};
use crate::uf::UnionFind;
use rayon::prelude::*;
use septa_exact::Sign;

/// What the pair test still has to show for the certificate to hold: that
/// no two triangles meet that are on the outer surface in different cells
/// ([`Self::outer_wanted`]), or in one cell that is not star-shaped (all its
/// pairs but those of two outer triangles, which the outer surface's test
/// takes). Two triangles of one star-shaped cell are proven apart by its
/// shape, on the outer surface too.
#[derive(Debug)]
pub(crate) struct TilingPlan {
    /// The outer surface's triangles (indices into the checked triangles).
    pub(crate) outer: Vec<u32>,
    /// The cell of each of `outer`.
    outer_cell: Vec<u32>,
    /// Per cell: star-shaped.
    star: Vec<bool>,
    /// Per cell that is not star-shaped: its triangles and whether each is
    /// inside (on a face between two cells).
    pub(crate) open: Vec<(Vec<u32>, Vec<bool>)>,
}

impl TilingPlan {
    /// Must the pair of outer triangles `a`, `b` (indices into `outer`) be
    /// tested?
    #[inline]
    pub(crate) fn outer_wanted(&self, a: usize, b: usize) -> bool {
        let (c, d) = (self.outer_cell[a], self.outer_cell[b]);
        c != d || !self.star[c as usize]
    }

    /// Cells found star-shaped.
    pub(crate) fn star_cells(&self) -> usize {
        self.star.iter().filter(|&&s| s).count()
    }
}

/// No cell (the first and second user of a face).
const NONE_A: u32 = u32::MAX;
const NONE_B: u32 = u32::MAX - 1;

/// The plan of the certificate for cells given as references to faces
/// (`refs[ref_start[c]..ref_start[c + 1]]`, each a face id and whether the
/// cell uses it reversed), face `f` being the triangles
/// `tris[tri_start[f]..tri_start[f + 1]]` (none degenerate); `None` when
/// conditions 1 or 2 of the module doc fail, or too few triangles are
/// inside for the certificate to pay ([`MIN_INTERIOR_SHARE`]); the caller
/// then tests every pair.
pub(crate) fn tiling_plan(
    x: &[[f64; 3]],
    tris: &[[u32; 3]],
    tri_start: &[u32],
    refs: &[(u32, bool)],
    ref_start: &[u32],
) -> Option<TilingPlan> {
    let nf = tri_start.len() - 1;
    let nc = ref_start.len() - 1;
    // condition 1: the cells using each face
    let mut users = vec![[NONE_A, NONE_B]; nf];
    let mut reversed = vec![false; nf];
    for c in 0..nc {
        for &(f, rev) in &refs[ref_start[c] as usize..ref_start[c + 1] as usize] {
            let u = &mut users[f as usize];
            if u[0] == NONE_A {
                (u[0], reversed[f as usize]) = (c as u32, rev);
            } else if u[1] == NONE_B && rev != reversed[f as usize] && u[0] != c as u32 {
                u[1] = c as u32;
            } else {
                return None;
            }
        }
    }
    // the certificate's own cost grows with all triangles, what it spares
    // with those inside (on many large meshes cut by few planes most
    // triangles are on the outer surface, many of them input triangles
    // whose pairs an earlier check already knows)
    let interior: usize =
        (0..nf).filter(|&f| users[f][1] != NONE_B).map(|f| (tri_start[f + 1] - tri_start[f]) as usize).sum();
    if interior * MIN_INTERIOR_SHARE < tris.len() {
        return None;
    }
    let oriented = |f: usize, rev: bool| {
        tris[tri_start[f] as usize..tri_start[f + 1] as usize]
            .iter()
            .map(move |t| if rev { [t[0], t[2], t[1]] } else { *t })
    };
    // conditions 2 and 3 per cell
    let shapes: Vec<Option<bool>> = (0..nc)
        .into_par_iter()
        .map_init(Vec::new, |buf: &mut Vec<[u32; 3]>, c| {
            buf.clear();
            for &(f, rev) in &refs[ref_start[c] as usize..ref_start[c + 1] as usize] {
                buf.extend(oriented(f as usize, rev));
            }
            let surface = Surface::new(buf)?;
            surface.connected_manifold().then(|| surface.star_shaped(x))
        })
        .collect();
    if shapes.iter().any(Option::is_none) {
        return None;
    }
    // condition 2 for the outer surface
    let outer: Vec<[u32; 3]> =
        (0..nf).filter(|&f| users[f][1] == NONE_B).flat_map(|f| oriented(f, reversed[f])).collect();
    if !Surface::new(&outer).is_some_and(|s| s.connected_manifold()) {
        return None;
    }
    let star: Vec<bool> = shapes.iter().map(|s| *s == Some(true)).collect();
    let mut plan = TilingPlan { outer: Vec::new(), outer_cell: Vec::new(), star, open: Vec::new() };
    let mut open_index = vec![u32::MAX; nc];
    for (c, _) in plan.star.iter().enumerate().filter(|(_, s)| !**s) {
        open_index[c] = plan.open.len() as u32;
        plan.open.push((Vec::new(), Vec::new()));
    }
    for f in 0..nf {
        let [a, b] = users[f];
        let boundary = b == NONE_B;
        for t in tri_start[f]..tri_start[f + 1] {
            if boundary {
                plan.outer.push(t);
                plan.outer_cell.push(a);
            }
            for c in [a, b] {
                if let Some(&i) = open_index.get(c as usize).filter(|&&i| i != u32::MAX) {
                    plan.open[i as usize].0.push(t);
                    plan.open[i as usize].1.push(!boundary);
                }
            }
        }
    }
    Some(plan)
}

/// The plan is made only when at least one triangle in this many is on a
/// face between two cells: below that it cost more than it spared (whole
/// run, one thread: armadillo A10, a tenth inside, +11%; rocker_arm A10, a
/// fifth, -8%). Certification ms without the plan / with it, after the
/// kernels were found better: bumpy_cube R20 (14.6% inside) 77 / 57, A10
/// (15.1%) 64 / 53; armadillo43k R20 (13.9%) 92 / 90, A10 (14.2%) 75 / 79;
/// armadillo and nefertiti (10-12%) 5-15% slower with it.
const MIN_INTERIOR_SHARE: usize = 7;

/// Projections of [`Surface::kernel_point`] before it gives up.
const KERNEL_ROUNDS: usize = 24;

/// How far past the most violated plane [`Surface::kernel_point`] moves
/// the point, as a multiple of its distance to that plane: over-relaxed
/// projections (Agmon; Motzkin and Schoenberg, 1954: any factor in (0, 2)
/// converges for a feasible system). Plain projections (1) zigzagged between
/// the walls of a cell holding part of a hole: on plate_genus9, of the
/// cells that were not found star-shaped, 20 of 46 (R20) and 22 of 51 (A10)
/// have a kernel (a linear program says so); 16 plain projections found
/// none of them, 24 of these steps find all (a sweep of factors 1.5-1.9
/// and 16-256 rounds on those cells).
const KERNEL_RELAXATION: f64 = 1.7;

/// Sorts `(key, value)` entries by key: a comparison sort when short, the
/// radix sort when long.
fn sort_entries(v: &mut Vec<(u64, u32)>) {
    if v.len() < 512 {
        v.sort_unstable();
    } else {
        radix_sort_keys(v);
    }
}

/// A closed oriented triangle surface in which every edge is used by exactly
/// two triangles, once in each direction; the edge leaving corner `c`
/// (`triangle * 3 + k`, running `t[k] -> t[k + 1]`) has its reverse
/// leaving corner `twin[c]`.
pub(crate) struct Surface<'a> {
    tris: &'a [[u32; 3]],
    twin: Vec<u32>,
}

impl<'a> Surface<'a> {
    /// `None` when some edge is not used exactly once in each direction
    /// (or the surface is empty or too large to index).
    pub(crate) fn new(tris: &'a [[u32; 3]]) -> Option<Surface<'a>> {
        if tris.is_empty() || tris.len() >= 1 << 30 {
            return None;
        }
        let mut edges: Vec<(u64, u32)> = Vec::with_capacity(3 * tris.len());
        for (i, t) in tris.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edges.push(((u64::from(a.min(b)) << 32) | u64::from(a.max(b)), (3 * i + k) as u32));
            }
        }
        sort_entries(&mut edges);
        let from = |c: u32| tris[c as usize / 3][c as usize % 3];
        let mut twin = vec![0u32; 3 * tris.len()];
        for (i, pair) in edges.chunks(2).enumerate() {
            let &[(k1, c1), (k2, c2)] = pair else { return None };
            if k1 != k2 || edges.get(2 * i + 2).is_some_and(|e| e.0 == k1) || from(c1) == from(c2) {
                return None;
            }
            (twin[c1 as usize], twin[c2 as usize]) = (c2, c1);
        }
        Some(Surface { tris, twin })
    }

    fn vertex(&self, corner: usize) -> u32 {
        self.tris[corner / 3][corner % 3]
    }

    /// The corner at `v` of a triangle `v a b` leads, around `v`, to the
    /// corner at `v` of the triangle `v b c`: the one leaving by the reverse
    /// of the edge `b -> v` (which leaves the corner after next).
    fn next_around(&self, corner: usize) -> usize {
        let (t, k) = (corner / 3, corner % 3);
        self.twin[3 * t + (k + 2) % 3] as usize
    }

    /// Is the surface connected, with the triangles around each vertex one
    /// fan (a 2-manifold)?
    pub(crate) fn connected_manifold(&self) -> bool {
        let m = self.tris.len();
        let mut faces = UnionFind::new(m);
        let mut components = m;
        let mut fan_vertices: Vec<u32> = Vec::new();
        let mut done = vec![false; 3 * m];
        for start in 0..3 * m {
            if done[start] {
                continue;
            }
            // the corners around one vertex form a cycle of `next_around`
            // (a permutation of the corners at that vertex)
            fan_vertices.push(self.vertex(start));
            let mut c = start;
            loop {
                done[c] = true;
                let n = self.next_around(c);
                let (f1, f2) = (faces.find((c / 3) as u32), faces.find((n / 3) as u32));
                if f1 != f2 {
                    faces.union(f1, f2);
                    components -= 1;
                }
                if n == start {
                    break;
                }
                c = n;
            }
        }
        // one fan per vertex
        fan_vertices.sort_unstable();
        components == 1 && fan_vertices.windows(2).all(|w| w[0] != w[1])
    }

    /// Is the surface, a closed connected manifold, star-shaped around the
    /// centroid of its volume or else around the mean of its corners,
    /// exactly (module doc)? `false` says nothing about the surface.
    pub(crate) fn star_shaped(&self, x: &[[f64; 3]]) -> bool {
        let mut q = [0.0; 3];
        for &v in self.tris.iter().flatten() {
            for k in 0..3 {
                q[k] += x[v as usize][k];
            }
        }
        let q = q.map(|s| s / (3 * self.tris.len()) as f64);
        // the centroid of the volume (tetrahedra from the corner mean)
        let (mut c, mut w) = ([0.0; 3], 0.0);
        for t in self.tris {
            let (a, b, d) = (sub(x[t[0] as usize], q), sub(x[t[1] as usize], q), sub(x[t[2] as usize], q));
            let vol = dot(a, cross(b, d));
            for k in 0..3 {
                c[k] += vol * (a[k] + b[k] + d[k]);
            }
            w += vol;
        }
        let centroid: [f64; 3] = std::array::from_fn(|k| q[k] + c[k] / (4.0 * w));
        self.star_shaped_around(x, centroid)
            || self.star_shaped_around(x, q)
            || self.kernel_point(x, centroid).is_some_and(|k| self.star_shaped_around(x, k))
    }

    /// A point on the inner side of every triangle's plane, in floating
    /// point, sought from `q` by moving it past the most violated plane,
    /// a few times (relaxation for linear inequalities,
    /// [`KERNEL_RELAXATION`]); only a guess,
    /// which [`Self::star_shaped_around`] decides exactly.
    fn kernel_point(&self, x: &[[f64; 3]], mut q: [f64; 3]) -> Option<[f64; 3]> {
        let planes: Vec<([f64; 3], f64)> = self
            .tris
            .iter()
            .map(|t| {
                let (a, b, c) = (x[t[0] as usize], x[t[1] as usize], x[t[2] as usize]);
                let n = cross(sub(b, a), sub(c, a));
                let n = scale(n, 1.0 / norm(n));
                (n, dot(n, a))
            })
            .collect();
        // a margin of a thousandth of the cell's size
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        for &v in self.tris.iter().flatten() {
            for k in 0..3 {
                lo[k] = lo[k].min(x[v as usize][k]);
                hi[k] = hi[k].max(x[v as usize][k]);
            }
        }
        let margin = 1e-3 * (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
        for _ in 0..KERNEL_ROUNDS {
            let worst = planes.iter().map(|&(n, d)| (dot(n, q) - d + margin, n)).max_by(|a, b| a.0.total_cmp(&b.0))?;
            if worst.0 <= 0.0 {
                return Some(q);
            }
            q = std::array::from_fn(|k| q[k] - KERNEL_RELAXATION * worst.0 * worst.1[k]);
        }
        None
    }

    /// Is the surface, a closed connected manifold, star-shaped around `q`?
    pub(crate) fn star_shaped_around(&self, x: &[[f64; 3]], q: [f64; 3]) -> bool {
        if !q.iter().all(|c| c.is_finite()) {
            return false;
        }
        let p = |v: u32| x[v as usize];
        let sign = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| orient(&[a, b, c, d], 0, 1, 2, 3);
        // (a) q strictly on the inner side of every triangle's plane
        if !self.tris.iter().all(|t| sign(p(t[0]), p(t[1]), p(t[2]), q) == Sign::Negative) {
            return false;
        }
        // (b) around each vertex v the fan a_1 .. a_k turns once about the
        // axis q -> v: signs of orient(q, v, a_1, a_i) run + .. + [0] - .. -
        let mut done = vec![false; 3 * self.tris.len()];
        for start in 0..3 * self.tris.len() {
            if done[start] {
                continue;
            }
            let (t, k) = (start / 3, start % 3);
            let (pv, a1) = (p(self.vertex(start)), self.tris[t][(k + 1) % 3]);
            let pa1 = p(a1);
            let (mut c, mut zero, mut negative) = (start, false, false);
            loop {
                done[c] = true;
                let a = self.tris[c / 3][(c % 3 + 2) % 3];
                if a == a1 {
                    break;
                }
                match sign(q, pv, pa1, p(a)) {
                    Sign::Positive if !zero && !negative => {}
                    Sign::Zero if !zero && !negative => zero = true,
                    Sign::Negative => negative = true,
                    _ => return false,
                }
                c = self.next_around(c);
                if done[c] {
                    return false;
                }
            }
            if !negative {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
#[path = "tiling_tests.rs"]
mod tests;
