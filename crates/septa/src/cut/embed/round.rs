//! Where each cut-vertex starts in the floating-point embedding (TopoCut
//! Sec. 6.1): its exact point rounded (from one interval evaluation of its
//! homogeneous coordinates, or from the exact coordinates when those
//! intervals are wide), snapped onto the axis-aligned planes of its triple,
//! and an interval box enclosing the exact point, which the embedding's
//! moves, the void attachment and the volume signs use.

use crate::cut::base::geom::{Ctx, Def};
use crate::cut::embed::side_filter::exact_box;
use septa_exact::{Interval, Sign};

/// The rounded position of a cut-vertex (nearest to exact up to the
/// rounding of its homogeneous coordinates) and an interval box enclosing
/// its exact point, from one interval evaluation of the coordinates.
pub fn round(c: &Ctx, d: Def) -> ([f64; 3], Option<[Interval; 3]>) {
    let (mut x, b) = round_unsnapped(c, d);
    snap_axis_planes(c, d, &mut x);
    (x, b)
}

/// Puts a cut-vertex exactly on each axis-aligned plane of its triple whose
/// offset is a double (`x = c` planes, as in TopoCut's An sets): that double
/// is the correct rounding of the exact coordinate, and it keeps every face
/// in such a plane exactly planar in the written doubles. Checked exactly
/// (`plane_point_sign` = 0) before it is kept.
pub fn snap_axis_planes(c: &Ctx, d: Def, x: &mut [f64; 3]) {
    let ps: &[u32] = match &d {
        Def::V(_) => return,
        Def::EP(_, p) => std::slice::from_ref(p),
        Def::TPP(_, p, q) => &[*p, *q],
        Def::PPP(p, q, r) => &[*p, *q, *r],
    };
    for &p in ps {
        let pl = c.planes[p as usize];
        let nz: Vec<usize> = (0..3).filter(|&k| pl[k] != 0.0).collect();
        if let [k] = nz[..] {
            let old = x[k];
            x[k] = -pl[3] / pl[k];
            if !x[k].is_finite() || septa_exact::plane_point_sign(&pl, x) != Sign::Zero {
                x[k] = old;
            }
        }
    }
}

fn round_unsnapped(c: &Ctx, d: Def) -> ([f64; 3], Option<[Interval; 3]>) {
    if let Def::V(v) = d {
        let x = c.verts[v as usize];
        return (x, Some(x.map(Interval::point)));
    }
    let (h, w) = c.hom::<Interval>(d);
    let m = w.mid();
    let guess = [h[0].mid() / m, h[1].mid() / m, h[2].mid() / m];
    let bx = exact_box(&h, &w);
    // An ill-conditioned triple (nearly parallel planes, W nearly 0) has
    // wide intervals and a midpoint quotient that can be far off (a point
    // of the line z = 1/2 of two planes at angle 2^-60 came out at z = 3):
    // then the rounding comes from the exact coordinates.
    let tight = bx.as_ref().is_some_and(|b| (0..3).all(|k| b[k].hi - b[k].lo <= 8.0 * ulp(&guess)));
    if tight && guess.iter().all(|x| x.is_finite()) {
        return (guess, bx);
    }
    (crate::cut::embed::exact_round::exact_rounding(c, d).unwrap_or_else(|| c.approx(d)), bx)
}

pub(crate) fn ulp(x: &[f64; 3]) -> f64 {
    let m = x.iter().fold(f64::MIN_POSITIVE, |m, c| m.max(c.abs()));
    f64::from_bits(m.to_bits() + 1) - m
}
