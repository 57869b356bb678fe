//! Certification of a result's written doubles: the exact check
//! (`check.rs`), then repairs that keep every count of the network, each
//! kept only where the exact check around it improves (`local.rs`), then
//! the exact check again, which is the certificate.
//!
//! The repairs, in order:
//! 1. *snap* (done by the caller, which knows the vertices' grid elements):
//!    coordinates that the exact vertex shares with its grid element (a
//!    vertex on a grid edge parallel to x has that edge's y and z) are set
//!    to the grid's doubles; interpolation could miss them by an ulp;
//! 2. *re-fan*: a polygon holding an offending triangle is fanned from
//!    another of its vertices (its loop rotated: the same polygon, other
//!    triangles; the writers fan from the first vertex);
//! 3. *nudge*: a vertex of an offending triangle, or one of two vertices at
//!    one point, moves towards the mean of its neighbours along its polygons'
//!    edges by a growing fraction `2^-40 .. 2^-3` of the way, keeping the
//!    coordinates it shares with the grid's box; the first fraction that
//!    clears the exact check around it is kept (or the best that improves
//!    it).
//!
//! Rounds of re-fans and nudges follow each full check, up to four.

use std::time::Instant;

use super::check::{check, Findings, Polygons};
use super::local::{violations_around, TriGrid};
use crate::network::embedding::Embedding;

/// Polygons and points to certify in place.
pub(crate) struct Target<'a> {
    pub points: &'a mut [[f64; 3]],
    pub start: &'a [u32],
    pub verts: &'a mut [u32],
    pub cells: Option<&'a [[u32; 2]]>,
    /// The grid's box, when the polygons are closed by it.
    pub bounds: Option<[[f64; 3]; 2]>,
    /// Vertices never to move (none: any may move).
    pub fixed: Option<&'a [bool]>,
}

/// The fractions of the way to the neighbours' mean a nudge tries.
const STEPS: [f64; 9] = [
    1.0 / (1u64 << 40) as f64,
    1.0 / (1u64 << 32) as f64,
    1.0 / (1u64 << 26) as f64,
    1.0 / (1u64 << 20) as f64,
    1.0 / (1u64 << 15) as f64,
    1.0 / (1u64 << 11) as f64,
    1.0 / 256.0,
    1.0 / 32.0,
    1.0 / 8.0,
];

/// The full check of `t` as it is now.
fn full(t: &Target) -> Findings {
    let p = Polygons { start: t.start, verts: t.verts, cells: t.cells };
    check(t.points, &p, t.bounds)
}

/// Certifies `t` (module doc); the report of what changed, with the check
/// before and after.
pub(crate) fn certify(t: &mut Target) -> Embedding {
    let t0 = Instant::now();
    let mut out = Embedding::default();
    let mut found = full(t);
    out.before = found.check.clone();
    for _round in 0..4 {
        if found.check.violations() == 0 || found.check.nonfinite_points > 0 {
            break;
        }
        let before = found.check.violations();
        let mut work = Work::new(t, &found);
        work.refan(t, &found);
        work.nudge(t, &found);
        out.rotated += work.rotated;
        out.nudged += work.nudged;
        out.largest_nudge = out.largest_nudge.max(work.largest);
        found = full(t);
        if found.check.violations() >= before && work.rotated + work.nudged == 0 {
            break;
        }
    }
    out.after = found.check;
    out.seconds = t0.elapsed().as_secs_f64();
    out
}

/// The fans as repairs change them: polygon `f` owns the triangle slots
/// `slot[f]..slot[f + 1]`, re-written when it is re-fanned.
struct Work {
    tris: Vec<[u32; 3]>,
    live: Vec<bool>,
    slot: Vec<u32>,
    grid: TriGrid,
    /// Polygons around each vertex (CSR).
    vp_start: Vec<u32>,
    vp: Vec<u32>,
    rotated: usize,
    nudged: usize,
    largest: f64,
}

impl Work {
    fn new(t: &Target, found: &Findings) -> Work {
        let nf = t.start.len() - 1;
        let mut slot = vec![0u32; nf + 1];
        for f in 0..nf {
            slot[f + 1] = slot[f] + (t.start[f + 1] - t.start[f]).saturating_sub(2);
        }
        let tris = found.fans.tris.clone();
        let grid = TriGrid::new(t.points, &tris);
        let mut vp_start = vec![0u32; t.points.len() + 1];
        for &v in t.verts.iter() {
            vp_start[v as usize + 1] += 1;
        }
        for i in 0..t.points.len() {
            vp_start[i + 1] += vp_start[i];
        }
        let mut fill = vp_start.clone();
        let mut vp = vec![0u32; t.verts.len()];
        for f in 0..nf {
            for &v in &t.verts[t.start[f] as usize..t.start[f + 1] as usize] {
                vp[fill[v as usize] as usize] = f as u32;
                fill[v as usize] += 1;
            }
        }
        let live = vec![true; tris.len()];
        Work { tris, live, slot, grid, vp_start, vp, rotated: 0, nudged: 0, largest: 0.0 }
    }

    fn slots(&self, f: usize) -> std::ops::Range<u32> {
        self.slot[f]..self.slot[f + 1]
    }

    /// Re-writes the fan of polygon `f` from its loop as it is now.
    fn write_fan(&mut self, t: &Target, f: usize) {
        let l = &t.verts[t.start[f] as usize..t.start[f + 1] as usize];
        for (i, s) in self.slots(f).enumerate() {
            self.tris[s as usize] = [l[0], l[i + 1], l[i + 2]];
            self.grid.insert(t.points, s, &self.tris[s as usize]);
        }
    }

    fn around(&mut self, t: &Target, group: &[u32], points: &[u32]) -> usize {
        violations_around(t.points, &self.tris, &self.live, &mut self.grid, group, points)
    }

    /// Polygons holding an offending triangle, fanned from the vertex that
    /// clears the exact check around them (or improves it most).
    fn refan(&mut self, t: &mut Target, found: &Findings) {
        let mut polys: Vec<u32> = found.bad.iter().map(|&b| found.fans.poly[b as usize]).collect();
        polys.sort_unstable();
        polys.dedup();
        for f in polys {
            let f = f as usize;
            let n = (t.start[f + 1] - t.start[f]) as usize;
            if n < 4 {
                continue;
            }
            let group: Vec<u32> = self.slots(f).collect();
            let now = self.around(t, &group, &[]);
            if now == 0 {
                continue;
            }
            let (mut best, mut best_r) = (now, 0);
            let range = t.start[f] as usize..t.start[f + 1] as usize;
            for r in 1..n {
                t.verts[range.clone()].rotate_left(1);
                self.write_fan(t, f);
                let v = self.around(t, &group, &[]);
                if v < best {
                    (best, best_r) = (v, r);
                    if v == 0 {
                        break;
                    }
                }
            }
            // back to the start, then to the best rotation
            let done = if best == 0 { best_r } else { n - 1 };
            t.verts[range.clone()].rotate_right(done);
            t.verts[range].rotate_left(best_r);
            self.write_fan(t, f);
            if best_r != 0 {
                self.rotated += 1;
            }
        }
    }

    /// The live triangles holding `v` and the mean of its neighbours.
    fn star(&self, t: &Target, v: u32) -> (Vec<u32>, [f64; 3], f64) {
        let mut star = Vec::new();
        let (mut sum, mut n, mut longest) = ([0.0; 3], 0.0, 0.0f64);
        let p = t.points[v as usize];
        for &f in &self.vp[self.vp_start[v as usize] as usize..self.vp_start[v as usize + 1] as usize] {
            let f = f as usize;
            star.extend(self.slots(f).filter(|&s| self.tris[s as usize].contains(&v)));
            let l = &t.verts[t.start[f] as usize..t.start[f + 1] as usize];
            let i = l.iter().position(|&w| w == v).unwrap_or(0);
            for w in [l[(i + 1) % l.len()], l[(i + l.len() - 1) % l.len()]] {
                let q = t.points[w as usize];
                for k in 0..3 {
                    sum[k] += q[k];
                }
                n += 1.0;
                longest = longest.max(((0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>()).sqrt());
            }
        }
        star.sort_unstable();
        star.dedup();
        (star, sum.map(|s| if n > 0.0 { s / n } else { 0.0 }), longest)
    }

    /// Vertices of offending triangles and of coincident pairs, each moved
    /// where the exact check around it clears (module doc).
    fn nudge(&mut self, t: &mut Target, found: &Findings) {
        let mut verts: Vec<u32> = Vec::new();
        for &b in &found.bad {
            let f = found.fans.poly[b as usize] as usize;
            // the polygon may have been re-fanned: its vertices now
            verts.extend_from_slice(&t.verts[t.start[f] as usize..t.start[f + 1] as usize]);
        }
        verts.extend(found.coincident.iter().flatten());
        verts.sort_unstable();
        verts.dedup();
        let on_box = |p: &[f64; 3], k: usize| t.bounds.is_some_and(|b| p[k] == b[0][k] || p[k] == b[1][k]);
        for v in verts {
            if t.fixed.is_some_and(|fx| fx[v as usize]) {
                continue;
            }
            let (star, mean, longest) = self.star(t, v);
            if star.is_empty() {
                continue;
            }
            let now = self.around(t, &star, &[v]);
            if now == 0 {
                continue;
            }
            let p = t.points[v as usize];
            let dir: [f64; 3] = std::array::from_fn(|k| if on_box(&p, k) { 0.0 } else { mean[k] - p[k] });
            let (mut best, mut best_q) = (now, p);
            for s in STEPS {
                let q: [f64; 3] = std::array::from_fn(|k| p[k] + s * dir[k]);
                if q == p {
                    continue;
                }
                t.points[v as usize] = q;
                for &s in &star {
                    self.grid.insert(t.points, s, &self.tris[s as usize]);
                }
                let after = self.around(t, &star, &[v]);
                if after < best {
                    (best, best_q) = (after, q);
                    if after == 0 {
                        break;
                    }
                }
            }
            t.points[v as usize] = best_q;
            for &s in &star {
                self.grid.insert(t.points, s, &self.tris[s as usize]);
            }
            if best_q != p {
                self.nudged += 1;
                let d = (0..3).map(|k| (best_q[k] - p[k]).powi(2)).sum::<f64>().sqrt();
                if longest > 0.0 {
                    self.largest = self.largest.max(d / longest);
                }
            }
        }
    }
}
