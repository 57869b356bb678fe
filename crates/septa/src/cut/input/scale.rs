//! Inputs at any double scale, and the memory a cut needs at least, both
//! decided before any cutting.
//!
//! **Scale.** The combinatorics of the cut are invariant under scaling
//! every coordinate by a power of two: each predicate's sign is the sign of
//! a polynomial that is homogeneous in the coordinates, and multiplying a
//! double by `2^k` is exact (outside the subnormal range). The floating
//! point parts are not invariant: the embedding's arithmetic overflows for
//! a mesh scaled by 1e300 (cells full of NaN, "check ok") and underflows
//! for one scaled by 1e-200 (intersecting cells, and the filters failing
//! on every predicate: 16-29 s). So a mesh whose largest coordinate lies
//! outside `[2^-64, 2^64]` is cut as its copy scaled by `2^k` into
//! `[0.5, 1)` (planes `a x + b y + c z + d = 0` become `d 2^k`), and the
//! results are scaled back by `2^-k`. A scaling that would not be exact
//! (a coordinate that would fall into the subnormals) or a plane too far
//! from the mesh to be cut in doubles is refused up front with the range.
//!
//! **Memory.** The plane-pair tables (`Ctx::pp_iv`, `Ctx::pp_b`: three
//! intervals and three bounded doubles per ordered pair, and the pairs'
//! crossing flags) grow with the square of the plane count, and the
//! plane-vertex signs with planes times vertices: a lower bound of what a
//! cut allocates, checked against the memory budget
//! ([`crate::grid::memory`]) before anything is allocated (before:
//! `--grid 2000` ran 136 s, then aborted in the allocator at 2.8 GB).

use std::borrow::Cow;

use crate::cut::{CutCellMesh, CutError};

/// Largest coordinate magnitude cut without scaling (and its inverse the
/// smallest): inside, inputs run exactly as given.
const COMFORT: f64 = 18446744073709551616.0; // 2^64

/// Farthest a plane may lie from the mesh, in units of the scaled mesh's
/// extent (`|d| / max(|a|, |b|, |c|)`): the cut-vertices' homogeneous
/// coordinates are products of up to four such values.
const FAR: f64 = 1.6069380442589903e60; // 2^200

/// `x * 2^k`, exactly when the result is normal (`k` may exceed the
/// exponent range of one double: two steps).
fn ldexp(x: f64, k: i32) -> f64 {
    let step = |x: f64, k: i32| x * f64::from_bits(((1023 + k) as u64) << 52);
    let half = k / 2;
    step(step(x, half), k - half)
}

/// The exponent `e` with `2^e <= |x| < 2^(e+1)` of a finite nonzero `x`.
fn exponent(x: f64) -> i32 {
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased == 0 {
        // subnormal: the leading bit's place
        -1074 + (63 - bits.leading_zeros() as i32)
    } else {
        biased - 1023
    }
}

/// The input of a cut, scaled into the comfortable range when it is not
/// there already (the module documentation).
pub(crate) struct Scaled<'a> {
    /// The vertices cut.
    pub vertices: Cow<'a, [[f64; 3]]>,
    /// The planes cut.
    pub planes: Cow<'a, [[f64; 4]]>,
    /// Coordinates were multiplied by `2^k`.
    k: i32,
}

impl<'a> Scaled<'a> {
    /// The mesh and planes to cut; an error naming the range when no exact
    /// power-of-two scaling brings them into doubles the cut can handle.
    pub fn new(vertices: &'a [[f64; 3]], planes: &'a [[f64; 4]]) -> Result<Scaled<'a>, CutError> {
        let finite = |x: &f64| x.is_finite();
        let max = vertices.iter().flatten().copied().filter(finite).fold(0.0f64, |m, x| m.max(x.abs()));
        let out_of_comfort = |m: f64| m != 0.0 && !(1.0 / COMFORT..=COMFORT).contains(&m);
        let k = if out_of_comfort(max) { -exponent(max) - 1 } else { 0 };
        let vertices: Cow<[[f64; 3]]> = if k == 0 {
            Cow::Borrowed(vertices)
        } else {
            let mut out = Vec::with_capacity(vertices.len());
            for (v, p) in vertices.iter().enumerate() {
                let q = p.map(|x| ldexp(x, k));
                // exact only when scaling back restores the input
                if let Some(a) = (0..3).find(|&a| p[a].is_finite() && ldexp(q[a], -k) != p[a]) {
                    return Err(CutError::OutOfRange(format!(
                        "the mesh's coordinates span {:e} (vertex {v}) to {max:e}: scaled exactly by 2^{k} into [0.5, 1), vertex {v} would fall below the normal doubles; the cut handles meshes whose nonzero coordinates lie within a factor 2^1000 of each other",
                        p[a]
                    )));
                }
                out.push(q);
            }
            Cow::Owned(out)
        };
        let mut scaled_planes: Option<Vec<[f64; 4]>> = None;
        for (i, p) in planes.iter().enumerate() {
            if p.iter().any(|x| !x.is_finite()) {
                continue; // refused with its index by the planes' own check
            }
            let n = p[0].abs().max(p[1].abs()).max(p[2].abs());
            if n == 0.0 {
                continue;
            }
            // the plane times 2^m, normal's largest component in [1, 2), so
            // that `d 2^k` is measured in the scaled mesh's units
            let m = if k != 0 || out_of_comfort(n) { -exponent(n) } else { 0 };
            if m == 0 && k == 0 {
                if p[3].abs() > FAR * n * max.max(1.0) {
                    return Err(far(i, p, max));
                }
                continue;
            }
            let q = [ldexp(p[0], m), ldexp(p[1], m), ldexp(p[2], m), ldexp(ldexp(p[3], m), k)];
            let back = [ldexp(q[0], -m), ldexp(q[1], -m), ldexp(q[2], -m), ldexp(ldexp(q[3], -k), -m)];
            if back != *p {
                return Err(CutError::OutOfRange(format!(
                    "plane {i} {p:?}: scaled exactly with the mesh (coordinates times 2^{k}) it would leave the normal doubles; give its coefficients within a factor 2^1000 of each other"
                )));
            }
            if q[3].abs() > FAR {
                return Err(far(i, p, max));
            }
            scaled_planes.get_or_insert_with(|| planes.to_vec())[i] = q;
        }
        let planes = scaled_planes.map_or(Cow::Borrowed(planes), Cow::Owned);
        Ok(Scaled { vertices, planes, k })
    }

    /// Moves a result computed on the scaled input back to the input's
    /// scale: points by `2^-k`, volumes by `2^-3k`, and the planes as given
    /// (the same planes; `kept` are the input planes cut, in order). The
    /// triangles' normals stay as computed: they are directions, any
    /// positive multiple serves.
    pub fn restore(&self, m: &mut CutCellMesh, planes: &[[f64; 4]]) {
        if let Cow::Owned(_) = self.planes {
            let dropped: std::collections::HashSet<usize> = m.stats.dropped_planes.iter().map(|d| d.0).collect();
            m.planes = planes.iter().enumerate().filter(|(i, _)| !dropped.contains(i)).map(|(_, p)| *p).collect();
        }
        m.volume_sums_at_cut_scale = [m.cell_volumes.iter().sum(), m.mesh_volume];
        if self.k == 0 {
            return;
        }
        for p in &mut m.vertices {
            *p = p.map(|x| ldexp(x, -self.k));
        }
        m.mesh_volume = ldexp(m.mesh_volume, -3 * self.k);
        for v in &mut m.cell_volumes {
            *v = ldexp(*v, -3 * self.k);
        }
    }
}

fn far(i: usize, p: &[f64; 4], max: f64) -> CutError {
    CutError::OutOfRange(format!(
        "plane {i} {p:?} lies more than 2^200 times the mesh's extent ({max:e}) from the origin: it cannot meet the mesh, and its cut-vertices would overflow the doubles; remove it"
    ))
}

/// Refuses a cut whose plane tables alone exceed the memory budget (the
/// module documentation): `np` planes, `nv` vertices, `nt` triangles.
pub(crate) fn check_memory(np: usize, nv: usize, nt: usize) -> Result<(), CutError> {
    let (np, nv, nt) = (np as u64, nv as u64, nt as u64);
    // per ordered plane pair: [Interval; 3] + [Bounded; 3] (48 bytes each)
    // and a crossing flag; per plane and vertex a sign; per triangle its
    // normal in both filter types
    let needed = np
        .saturating_mul(np)
        .saturating_mul(97)
        .saturating_add(np.saturating_mul(nv))
        .saturating_add(nt.saturating_mul(96));
    crate::grid::memory::check(
        needed,
        || format!("cutting by {np} planes (their pair tables) a mesh of {nv} vertices"),
        "use fewer planes (a smaller --grid or --random)",
    )
    .map_err(|e| CutError::OutOfRange(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_powers_of_two() {
        assert_eq!(ldexp(3.0, 1100 - 1000), 3.0 * 2f64.powi(100));
        assert_eq!(ldexp(1e300, -1100), 1e300 * 2f64.powi(-550) * 2f64.powi(-550));
        assert_eq!(exponent(1.0), 0);
        assert_eq!(exponent(0.75), -1);
        assert_eq!(exponent(f64::MIN_POSITIVE), -1022);
        assert_eq!(exponent(f64::from_bits(1)), -1074);
        assert_eq!(exponent(1e300), 996);
        let cube = [[0.0, 0.0, 0.0], [1e300, 2e300, 0.0], [-3e300, 0.0, 1e300]];
        let planes = [[1.0, 0.0, 0.0, -1e300], [0.0, 2.0, 0.0, 0.0]];
        let s = Scaled::new(&cube, &planes).unwrap();
        assert!(s.vertices.iter().flatten().all(|x| x.abs() < 1.0));
        assert_eq!(s.vertices[2][0], ldexp(-3e300, s.k));
        // the same plane: x = 1e300 in the scaled units
        assert_eq!(s.planes[0][3], ldexp(-1e300, s.k));
        // comfortable inputs are not copied
        let unit = [[0.0, 1.0, 2.0]];
        assert!(matches!(Scaled::new(&unit, &planes[1..]).unwrap().vertices, Cow::Borrowed(_)));
        // a coordinate that cannot be scaled exactly, a plane too far
        assert!(Scaled::new(&[[1e300, 0.0, 1e-300]], &[]).is_err());
        assert!(Scaled::new(&unit, &[[1.0, 0.0, 0.0, 1e100]]).is_err());
        assert!(check_memory(6000, 8, 12).is_err() || crate::grid::memory::budget().0 > 3_000_000_000);
        assert!(check_memory(10, 8, 12).is_ok());
    }
}
