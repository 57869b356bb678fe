//! Where remeshed vertices are put back: the unremeshed surface (the
//! closest point on the vertex's patch, or on its constraint curve).

use super::original::{On, Original};
use super::soup::{Kind, V};

pub(super) struct Surface {
    pub orig: Original,
}

impl Surface {
    pub(super) fn place(&self, kind: Kind, p: V) -> V {
        match kind {
            Kind::Fixed => p,
            Kind::Curve(t) => self.orig.closest(p, On::Trace(t)),
            Kind::Free(q) => self.orig.closest(p, On::Patch(q)),
        }
    }
}
