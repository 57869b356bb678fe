//! Where remeshed vertices are put back: the unremeshed surface (the
//! closest point on the vertex's patch, or on its constraint curve), then,
//! for a network of formulas, their true zero sets (`zeros.rs`).

use super::original::{On, Original};
use super::soup::{Kind, V};
use super::zeros::Zeros;

pub(super) struct Surface<'a> {
    pub orig: Original,
    /// The formulas the network came from (then the true zero sets).
    pub zeros: Option<Zeros<'a>>,
}

impl Surface<'_> {
    pub(super) fn place(&self, kind: Kind, p: V) -> V {
        let q = match kind {
            Kind::Fixed => return p,
            Kind::Curve(t) => self.orig.closest(p, On::Trace(t)),
            Kind::Free(q) => self.orig.closest(p, On::Patch(q)),
        };
        let Some(z) = &self.zeros else { return q };
        let on = match kind {
            Kind::Curve(t) => z.trace.get(t as usize).and_then(|(eqs, fixed)| {
                let free = fixed.iter().filter(|&&f| !f).count();
                // a curve: two equations, or one within a side of the box
                (eqs.len() + 3 - free >= 2 && !eqs.is_empty()).then(|| z.onto(&eqs[..eqs.len().min(2)], *fixed, q))
            }),
            Kind::Free(p) => z.patch.get(p as usize).map(|&e| z.onto(&[e], [false; 3], q)),
            Kind::Fixed => None,
        };
        on.flatten().unwrap_or(q)
    }
}
