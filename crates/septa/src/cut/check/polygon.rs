//! Exact facts of one polygon of doubles that the check and the cut's output
//! ask for: is a corner triple degenerate (collinear), is the polygon
//! planar (every vertex exactly on the plane of its first non-collinear
//! corner triple), and the floating-point Newell normal that orients the
//! projection of an ear clipping.

use crate::cut::triangles::orient::{orient, orient2};
use septa_exact::Sign;

/// Is the triangle `a b c` degenerate (collinear corners, exactly)?
pub(crate) fn collinear(x: &[[f64; 3]], a: u32, b: u32, c: u32) -> bool {
    (0..3).all(|k| orient2(x, k, a, b, c) == Sign::Zero)
}

/// Is the polygon exactly planar? `None` when it is degenerate (fewer than
/// three distinct vertices or all corners collinear).
pub fn polygon_planar(x: &[[f64; 3]], poly: &[u32]) -> Option<bool> {
    if poly.len() < 3 {
        return None;
    }
    let (a, b) = (poly[0], poly[1]);
    let c = *poly[2..].iter().find(|&&c| !collinear(x, a, b, c))?;
    Some(poly[2..].iter().all(|&v| v == c || orient(x, a, b, c, v) == Sign::Zero))
}

/// Newell normal of a polygon (floating point; only orients the projection
/// of the ear clipping).
pub(crate) fn newell(x: &[[f64; 3]], poly: &[u32]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for i in 0..poly.len() {
        let (p, q) = (x[poly[i] as usize], x[poly[(i + 1) % poly.len()] as usize]);
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}
