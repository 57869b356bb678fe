//! Cutting planes as quick separators for the exact triangle-pair test of
//! the check ([`crate::cut::triangles::selfx`]): most candidate pairs of a cut-cell mesh
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
//! rounding error ([`Separator::sides`]), else the bit stays clear and the
//! pair goes to the exact test as before. So the planes are hints: any set
//! of planes gives the same report, only the time changes.
//!
//! The thresholds are `c = +mu` and `c = -mu` for a small `mu` relative to
//! the mesh size: a cut-face on a plane has its rounded corners within a
//! few ulps of it, on either side, so it is proven in `{f < mu}` and in
//! `{f > -mu}`, while a triangle away from the plane is proven beyond the
//! threshold on its side. Triangles on one plane on both sides of a second
//! plane are separated by that second plane unless they touch; touching
//! pairs (no plane separates them) are left to the exact test, and among
//! them are its costliest, nearly coplanar neighbours.
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

/// One plane's function `f(p) = n . p + d`, its threshold `mu` and the
/// bound `e` on the rounding error of `f` at any vertex of the mesh.
#[derive(Clone, Copy, Debug)]
struct Separator {
    n: [f64; 3],
    d: f64,
    mu: f64,
    e: f64,
}

impl Separator {
    /// The plane `[a, b, c, d]` over vertices whose coordinates are at most
    /// `max_abs` in absolute value per axis; `None` when it cannot prove
    /// anything.
    ///
    /// Error bound: `g = fl(n0 p0 + n1 p1 + n2 p2 + d)`, summed left to
    /// right, differs from `f(p)` by at most `gamma_4 * S_p` with `S_p =
    /// |n0 p0| + |n1 p1| + |n2 p2| + |d|` and `gamma_4 = 4u / (1 - 4u)`, `u =
    /// 2^-53` (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd
    /// ed., Sec. 3.1, inner products). Every vertex has `S_p <= S = |n0| M0 +
    /// |n1| M1 + |n2| M2 + |d|` (`M` = `max_abs`), so one `e = 16u fl(S)`
    /// serves all, with room for the rounding of `fl(S)`, of `e` itself and
    /// of `g -+ mu` (a factor `1 + u` each). Products below the normal range
    /// lose an absolute `2^-1075` at most, covered once `S > 2^-900`; a
    /// smaller or non-finite `S` gives no separator.
    fn new(p: &[f64; 4], max_abs: &[f64; 3], scale: f64) -> Option<Separator> {
        const U: f64 = f64::EPSILON / 2.0;
        let n = [p[0], p[1], p[2]];
        let s = n[0].abs() * max_abs[0] + n[1].abs() * max_abs[1] + n[2].abs() * max_abs[2] + p[3].abs();
        let e = 16.0 * U * s;
        let mu = MU_RELATIVE * (n[0].abs() + n[1].abs() + n[2].abs()) * scale;
        let oblique = n.iter().filter(|&&c| c != 0.0).count() >= 2;
        (oblique && s > 1e-270 && e.is_finite() && mu > 0.0 && mu.is_finite()).then_some(Separator {
            n,
            d: p[3],
            mu,
            e,
        })
    }

    /// The sides of `p` claimed as proven: `[f > mu, f < mu, f < -mu, f >
    /// -mu]` (each compared after the subtraction: `fl(g - mu) > e` implies
    /// `g - mu > e / (1 + u)`, beyond the error of `g`). A NaN fails every
    /// comparison and claims nothing.
    #[inline]
    fn sides(&self, p: &[f64; 3]) -> [bool; 4] {
        let g = self.n[0] * p[0] + self.n[1] * p[1] + self.n[2] * p[2] + self.d;
        let (mu, e) = (self.mu, self.e);
        [g - mu > e, mu - g > e, -mu - g > e, g + mu > e]
    }
}

impl PlaneSeparation {
    /// The bits of `tris` (vertex ids into `x`, all finite) against
    /// `planes` (`[a, b, c, d]`: `a x + b y + c z + d = 0`); `None` when no
    /// plane can separate anything (all axis-aligned, degenerate or not
    /// finite).
    pub(crate) fn new(x: &[[f64; 3]], tris: &[[u32; 3]], planes: &[[f64; 4]]) -> Option<PlaneSeparation> {
        // (a NaN coordinate is passed over by `max`; an infinite one voids every plane)
        let mut max_abs = [0.0f64; 3];
        for p in x {
            for k in 0..3 {
                max_abs[k] = max_abs[k].max(p[k].abs());
            }
        }
        let scale = max_abs[0].max(max_abs[1]).max(max_abs[2]);
        let useful: Vec<Separator> =
            planes.iter().filter_map(|p| Separator::new(p, &max_abs, scale)).take(MAX_PLANES).collect();
        if useful.is_empty() {
            return None;
        }
        // plane after plane over a chunk of vertices
        let mut corner = vec![[0u64; 4]; x.len()];
        corner.par_chunks_mut(4096).zip(x.par_chunks(4096)).for_each(|(m, x)| {
            for (i, sep) in useful.iter().enumerate() {
                for (m, p) in m.iter_mut().zip(x) {
                    let s = sep.sides(p);
                    for k in 0..4 {
                        m[k] |= (s[k] as u64) << i;
                    }
                }
            }
        });
        let masks = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (&corner[t[0] as usize], &corner[t[1] as usize], &corner[t[2] as usize]);
                std::array::from_fn(|k| a[k] & b[k] & c[k])
            })
            .collect();
        Some(PlaneSeparation { masks })
    }

    /// The bits of the triangles `idx` (indices into the triangles given to
    /// [`Self::new`]), in that order.
    pub(crate) fn subset(&self, idx: &[u32]) -> PlaneSeparation {
        PlaneSeparation { masks: idx.iter().map(|&t| self.masks[t as usize]).collect() }
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
