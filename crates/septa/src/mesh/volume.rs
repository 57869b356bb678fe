//! Positive cell volumes, proven exactly on the written doubles.
//!
//! A cell of a grid network is bounded by polygons and, where it reaches
//! them, by the sides of the grid's box. With the field `F = (x_k - c) e_k`
//! (divergence 1) and `c` the box's low (or high) side on axis `k`, the
//! divergence theorem gives `volume = flux through the cell's triangles +
//! flux through the part of the box's boundary in the cell`; on the sides
//! across other axes `F . n = 0`, on the side at `c` `F = 0`, and on the
//! opposite side `F . n = |hi_k - lo_k| >= 0`. So the volume is at least the
//! flux through the triangles, and a positive flux proves a positive volume
//! (for a cell wholly inside the box the two are equal). Vertices on the
//! box must lie exactly on its planes for this (`certify.rs` puts them
//! there). Six times the flux through a triangle `(a, b, c)` is `(a_k + b_k
//! + c_k - 3c) N_k`, `N = (b - a) x (c - a)`; the sum over a cell's
//! triangles is one polynomial of the doubles, whose sign comes from
//! `septa_exact::filtered_sign_bounded` (a double with an error bound, then
//! intervals, then exact).
//!
//! A cell is checked when its polygons close it up to the box: every edge
//! of its polygons used as often in one direction as in the other, except
//! edges lying in a side of the box.

use rayon::prelude::*;
use septa_exact::{filtered_sign_bounded, Bounded, Exact, Interval, Ring, Sign};

use super::check::{Fans, Polygons};

/// The polygons of each cell, oriented outwards, and whether the cell is
/// closed up to the box.
pub(crate) struct CellFaces {
    start: Vec<u32>,
    /// (polygon, reversed): a polygon's loop is counter-clockwise seen from
    /// its positive side, so it is outward for the cell on its negative side.
    refs: Vec<(u32, bool)>,
    closed: Vec<bool>,
}

/// Is the segment `ab` in a side of the box (both ends exactly on one of
/// its planes)?
fn on_box(x: &[[f64; 3]], a: u32, b: u32, bounds: Option<[[f64; 3]; 2]>) -> bool {
    let Some(bb) = bounds else { return false };
    let (p, q) = (x[a as usize], x[b as usize]);
    (0..3).any(|k| bb.iter().any(|side| p[k] == side[k] && q[k] == side[k]))
}

impl CellFaces {
    pub fn new(p: &Polygons, cells: &[[u32; 2]], x: &[[f64; 3]], bounds: Option<[[f64; 3]; 2]>) -> CellFaces {
        let n = cells.iter().flatten().filter(|&&c| c != u32::MAX).map(|&c| c as usize + 1).max().unwrap_or(0);
        let mut count = vec![0u32; n + 1];
        for c in cells.iter().flatten().filter(|&&c| c != u32::MAX) {
            count[*c as usize + 1] += 1;
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let start = count.clone();
        let mut refs = vec![(0u32, false); count[n] as usize];
        for (f, &[pos, neg]) in cells.iter().enumerate() {
            for (c, reversed) in [(pos, true), (neg, false)] {
                if c != u32::MAX {
                    refs[count[c as usize] as usize] = (f as u32, reversed);
                    count[c as usize] += 1;
                }
            }
        }
        let closed = (0..n)
            .into_par_iter()
            .map(|c| {
                // (lo, hi, +1 when used from lo to hi outwards)
                let mut edges: Vec<(u32, u32, i32)> = Vec::new();
                for &(f, rev) in &refs[start[c] as usize..start[c + 1] as usize] {
                    let l = p.poly(f as usize);
                    for i in 0..l.len() {
                        let (mut a, mut b) = (l[i], l[(i + 1) % l.len()]);
                        if rev {
                            std::mem::swap(&mut a, &mut b);
                        }
                        edges.push((a.min(b), a.max(b), if a < b { 1 } else { -1 }));
                    }
                }
                edges.sort_unstable();
                edges
                    .chunk_by(|u, v| (u.0, u.1) == (v.0, v.1))
                    .all(|g| g.iter().map(|e| e.2).sum::<i32>() == 0 || on_box(x, g[0].0, g[0].1, bounds))
            })
            .collect();
        CellFaces { start, refs, closed }
    }
}

/// Six times the flux of `(x_k - c) e_k` through the triangles `tris`
/// (`true`: reversed), in the ring `R`.
fn flux<R: Ring>(x: &[[f64; 3]], tris: &[([u32; 3], bool)], k: usize, c: f64) -> R {
    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
    let mut sum = R::of(0.0);
    let cr = R::of(c);
    for &(t, rev) in tris {
        let [a, b, d] = t.map(|v| x[v as usize]);
        let e = |p: &[f64; 3], q: &[f64; 3], m: usize| R::of(q[m]).sub(&R::of(p[m]));
        let n = e(&a, &b, i).mul(&e(&a, &d, j)).sub(&e(&a, &b, j).mul(&e(&a, &d, i)));
        let h = R::of(a[k]).sub(&cr).add(&R::of(b[k]).sub(&cr)).add(&R::of(d[k]).sub(&cr));
        let term = h.mul(&n);
        sum = if rev { sum.sub(&term) } else { sum.add(&term) };
    }
    sum
}

/// The exact sign of [`flux`].
pub(super) fn flux_sign(x: &[[f64; 3]], tris: &[([u32; 3], bool)], k: usize, c: f64) -> Sign {
    filtered_sign_bounded(
        || flux::<Bounded>(x, tris, k, c),
        || flux::<Interval>(x, tris, k, c),
        || flux::<Exact>(x, tris, k, c),
    )
}

/// `(checked, proven positive)`: the cells closed up to the box, and those
/// among them whose volume a flux proves positive (module doc).
pub(crate) fn cell_fluxes_positive(
    x: &[[f64; 3]],
    faces: &CellFaces,
    fans: &Fans,
    bounds: Option<[[f64; 3]; 2]>,
) -> (usize, usize) {
    // the fans' triangles of each polygon are consecutive, in polygon order
    let mut tri_start = vec![0u32; fans.poly.last().map_or(0, |&f| f as usize + 1) + 1];
    for &f in &fans.poly {
        tri_start[f as usize + 1] += 1;
    }
    for i in 1..tri_start.len() {
        tri_start[i] += tri_start[i - 1];
    }
    let n = faces.closed.len();
    let proven: Vec<bool> = (0..n)
        .into_par_iter()
        .map(|c| {
            if !faces.closed[c] {
                return false;
            }
            let mut tris: Vec<([u32; 3], bool)> = Vec::new();
            for &(f, rev) in &faces.refs[faces.start[c] as usize..faces.start[c + 1] as usize] {
                let f = f as usize;
                if f + 1 < tri_start.len() {
                    let r = tri_start[f] as usize..tri_start[f + 1] as usize;
                    tris.extend(fans.tris[r].iter().map(|&t| (t, rev)));
                }
            }
            // the candidate fields, the largest floating-point flux first
            let sides: Vec<(usize, f64)> = match bounds {
                Some(b) => (0..3).flat_map(|k| [(k, b[0][k]), (k, b[1][k])]).collect(),
                None => vec![(0, 0.0)],
            };
            let mut est: Vec<(f64, usize, f64)> =
                sides.iter().map(|&(k, s)| (flux::<Plain>(x, &tris, k, s).0, k, s)).collect();
            est.sort_by(|a, b| b.0.total_cmp(&a.0));
            est.iter().filter(|e| e.0 > 0.0).any(|&(_, k, s)| flux_sign(x, &tris, k, s) == Sign::Positive)
        })
        .collect();
    (faces.closed.iter().filter(|&&c| c).count(), proven.iter().filter(|&&p| p).count())
}

/// Plain doubles as a [`Ring`], for the estimates that order the exact tries.
#[derive(Clone, Copy)]
struct Plain(f64);

impl Ring for Plain {
    fn of(x: f64) -> Self {
        Plain(x)
    }
    fn add(&self, o: &Self) -> Self {
        Plain(self.0 + o.0)
    }
    fn sub(&self, o: &Self) -> Self {
        Plain(self.0 - o.0)
    }
    fn mul(&self, o: &Self) -> Self {
        Plain(self.0 * o.0)
    }
    fn neg(&self) -> Self {
        Plain(-self.0)
    }
}

#[cfg(test)]
#[path = "volume_tests.rs"]
mod tests;
