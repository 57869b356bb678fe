//! Cutting planes as quick separators for the exact triangle-pair test of
//! the check ([`super::selfx`]): most candidate pairs of a cut-cell mesh
//! cut by oblique planes lie in different cells of the plane arrangement,
//! or one on a plane and the other away from it, and a cutting plane then
//! lies between them. Deciding that from bits per triangle replaces the
//! pair's box contact and plane-side tests (about a hundred cycles) by four
//! word operations.
//!
//! Why it is a proof: for an affine `f(p) = n . p + d` and a threshold `c`,
//! a triangle (the convex hull of its corners) lies in `{f > c}` iff its
//! three corners do, and likewise for `{f < c}`. If every corner of one
//! triangle has `f > c` and every corner of the other `f < c`, no point is
//! in both. Which plane and which `c` are used does not matter for the
//! proof, only that each corner's side is proven: a side is claimed only
//! when the floating-point value of `f(p) - c` exceeds a bound on its
//! rounding error ([`side_of`]), else the bit stays clear and the pair goes
//! to the exact test as before. So the planes are hints: any set of planes
//! gives the same report, only the time changes.
//!
//! The thresholds are `c = +mu` and `c = -mu` for a small `mu` relative to
//! the mesh size: a cut-face on a plane has its rounded corners within a
//! few ulps of it, on either side, so it is proven in `{f < mu}` and in
//! `{f > -mu}`, while a triangle away from the plane is proven beyond the
//! threshold on its side. Triangles on one plane on both sides of a second
//! plane (nearly coplanar neighbours, the costly pairs of the exact test)
//! are separated by that second plane.
//!
//! Axis-aligned planes are left out: two triangles whose boxes overlap are
//! never on opposite sides of a plane `x_k = c` (their ranges in `x_k`
//! overlap), so such planes could only cost time.

use rayon::prelude::*;

/// At most this many planes give bits (any subset of the planes is sound).
const MAX_PLANES: usize = 64;

/// The threshold `mu` relative to `|n|_1` times the largest coordinate:
/// far above the few ulps a rounded cut-vertex lies off its planes, far
/// below any feature of a mesh whose coordinates are doubles.
const MU_RELATIVE: f64 = 1.0 / (1u64 << 30) as f64;

/// Per triangle, the planes (bit `i`: plane `i` of the useful ones) whose
/// function is proven, at every corner:
/// `[f > mu, f < mu, f < -mu, f > -mu]`.
pub(crate) struct PlaneSeparation {
    masks: Vec<[u64; 4]>,
}

/// The sides of `p` against `f(p) = n . p + d` at the threshold `c`:
/// `(proven f(p) > c, proven f(p) < c)`; neither when the floating-point
/// value is within its error bound of `c` (or not finite).
///
/// Error bound: `g = fl(n0 p0 + n1 p1 + n2 p2 + d)`, summed left to right,
/// differs from `f(p)` by at most `gamma_4 * S` with `S = |n0 p0| + |n1 p1|
/// + |n2 p2| + |d|` and `gamma_4 = 4u / (1 - 4u)`, `u = 2^-53` (Higham,
/// "Accuracy and Stability of Numerical Algorithms", 2nd ed., Sec. 3.1,
/// inner products). `E = 8u fl(S)` covers it with room for the rounding of
/// `fl(S)`, of `E` itself and of `g - c` (each a factor `1 + u` at most).
/// Products below the normal range lose only an absolute `2^-1075` each,
/// covered by `E` once `S > 2^-900`; smaller `S` claims nothing. A NaN or
/// infinite value fails every comparison, so it claims nothing either.
#[inline]
fn side_of(n: &[f64; 3], d: f64, c: f64, p: &[f64; 3]) -> (bool, bool) {
    const U: f64 = f64::EPSILON / 2.0;
    let g = n[0] * p[0] + n[1] * p[1] + n[2] * p[2] + d;
    let s = (n[0] * p[0]).abs() + (n[1] * p[1]).abs() + (n[2] * p[2]).abs() + d.abs();
    let e = 8.0 * U * s;
    let tiny = !(s > 1e-270);
    (!tiny && g - c > e, !tiny && c - g > e)
}

impl PlaneSeparation {
    /// The bits of `tris` (vertex ids into `x`) against `planes`
    /// (`[a, b, c, d]`: `a x + b y + c z + d = 0`); `None` when no plane
    /// can separate anything (all axis-aligned, degenerate or not finite).
    pub(crate) fn new(x: &[[f64; 3]], tris: &[[u32; 3]], planes: &[[f64; 4]]) -> Option<PlaneSeparation> {
        let scale = x.iter().flatten().fold(0.0f64, |m, c| m.max(c.abs()));
        let useful: Vec<([f64; 3], f64, f64)> = planes
            .iter()
            .filter(|p| p.iter().all(|c| c.is_finite()) && p[..3].iter().filter(|&&c| c != 0.0).count() >= 2)
            .map(|p| ([p[0], p[1], p[2]], p[3], MU_RELATIVE * (p[0].abs() + p[1].abs() + p[2].abs()) * scale))
            .filter(|&(_, _, mu)| mu > 0.0 && mu.is_finite())
            .take(MAX_PLANES)
            .collect();
        if useful.is_empty() || !scale.is_finite() {
            return None;
        }
        let corner: Vec<[u64; 4]> = x
            .par_iter()
            .map(|p| {
                let mut m = [0u64; 4];
                for (i, (n, d, mu)) in useful.iter().enumerate() {
                    let (above, under) = side_of(n, *d, *mu, p);
                    let (over, below) = side_of(n, *d, -mu, p);
                    let b = 1u64 << i;
                    m[0] |= b * above as u64;
                    m[1] |= b * under as u64;
                    m[2] |= b * below as u64;
                    m[3] |= b * over as u64;
                }
                m
            })
            .collect();
        let masks = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (&corner[t[0] as usize], &corner[t[1] as usize], &corner[t[2] as usize]);
                std::array::from_fn(|k| a[k] & b[k] & c[k])
            })
            .collect();
        Some(PlaneSeparation { masks })
    }

    /// Is some plane proven to lie between triangles `a` and `b` (indices
    /// into the triangles given to [`Self::new`])? Then they are disjoint.
    #[inline]
    pub(crate) fn separated(&self, a: usize, b: usize) -> bool {
        let (p, q) = (&self.masks[a], &self.masks[b]);
        (p[0] & q[1]) | (p[1] & q[0]) | (p[2] & q[3]) | (p[3] & q[2]) != 0
    }
}

#[cfg(test)]
#[path = "plane_separation_tests.rs"]
mod tests;
