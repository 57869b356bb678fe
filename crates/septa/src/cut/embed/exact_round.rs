//! The rounding of a cut-vertex from its exact homogeneous coordinates
//! (TopoCut Sec. 6.1: cut-vertices are rounded from their exact triples),
//! used when the interval enclosure is too wide for its midpoint quotient
//! (`embed::round`).
//!
//! The coordinates `H / W` ([`Ctx::hom`]) are polynomials of at most five
//! input factors per product (`TPP`: a corner times the 2x2 determinant of
//! two plane normals against two triangle edges). Evaluated as stack
//! [`Expansion`]s (Shewchuk 1997) instead of heap bignums ([`Exact`]) when
//! every input is inside the expansions' exponent window: the same exact
//! values, rounded to doubles as `Exact::to_f64_approx` rounds them
//! (`Expansion::to_f64_approx`, tested against it), so the written doubles
//! are unchanged. On staircase R20 and plate_genus9 R20 a
//! quarter to an eighth of the cut-vertices take this path.
//!
//! Before either, the same `H` and `W` are evaluated in double-word
//! arithmetic with a proven error bound ([`DoubleWord`]); it gives the same
//! doubles whenever each enclosure lies between two steps of the rounding,
//! which is nearly always, at about half the cost of expansions.

use crate::cut::base::geom::{Ctx, Def};
use septa_exact::{expansion_window, DoubleWord, Exact, Expansion};

/// The doubles [`Ctx::hom`] reads for `d`.
fn inputs(c: &Ctx, d: Def) -> Vec<f64> {
    let mut xs: Vec<f64> = Vec::with_capacity(21);
    let mut verts = |vs: &[u32]| {
        for &v in vs {
            xs.extend_from_slice(&c.verts[v as usize]);
        }
    };
    let planes: &[u32] = match &d {
        Def::V(v) => {
            verts(&[*v]);
            &[]
        }
        Def::EP(e, p) => {
            verts(&c.edges[*e as usize]);
            std::slice::from_ref(p)
        }
        Def::TPP(t, p, q) => {
            verts(&c.tris[*t as usize]);
            &[*p, *q]
        }
        Def::PPP(p, q, r) => &[*p, *q, *r],
    };
    for &p in planes {
        xs.extend_from_slice(&c.planes[p as usize]);
    }
    xs
}

/// The rounding of `d` from its exact coordinates: each `H` component and
/// `W` to a double (`Exact::to_f64_approx`, computed from expansions where
/// they are exact and fit, else from bignums), then divided; `None` when a
/// quotient is not finite.
pub(crate) fn exact_rounding(c: &Ctx, d: Def) -> Option<[f64; 3]> {
    double_word_rounding(c, d).or_else(|| exact_rounding_from_exact_values(c, d))
}

/// [`exact_rounding`] from double-word enclosures of `H` and `W`, when
/// they decide every rounding (`None` sends the caller to the exact
/// values; `Some` with a non-finite coordinate is not claimed either).
fn double_word_rounding(c: &Ctx, d: Def) -> Option<[f64; 3]> {
    let (h, w) = c.hom::<DoubleWord>(d);
    let wf = w.to_f64_approx()?;
    let x = [h[0].to_f64_approx()? / wf, h[1].to_f64_approx()? / wf, h[2].to_f64_approx()? / wf];
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// [`exact_rounding`] from the exact values (expansions, else bignums).
fn exact_rounding_from_exact_values(c: &Ctx, d: Def) -> Option<[f64; 3]> {
    let fast = || -> Option<[f64; 4]> {
        if !expansion_window(inputs(c, d)) {
            return None;
        }
        let (h, w) = c.hom::<Expansion>(d);
        Some([h[0].to_f64_approx()?, h[1].to_f64_approx()?, h[2].to_f64_approx()?, w.to_f64_approx()?])
    };
    let [h0, h1, h2, wf] = fast().unwrap_or_else(|| {
        let (he, we) = c.hom::<Exact>(d);
        [he[0].to_f64_approx(), he[1].to_f64_approx(), he[2].to_f64_approx(), we.to_f64_approx()]
    });
    let x = [h0 / wf, h1 / wf, h2 / wf];
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
#[path = "exact_round_tests.rs"]
mod tests;
