//! Vertices where more planes meet than the ones that name them.
//!
//! With exact ties one point can lie on more planes than the `d` (IA) or
//! `d + 1` (MI) that define a vertex on a `d`-simplex (Sec. 5.1): a third
//! function vanishing where two others cross a tet face, three materials
//! tied at one point of a tet edge. Which of those planes the incremental
//! construction used depends on the insertion order and on which functions
//! are active in the tet, so two tets sharing the face or edge could name
//! one point differently, and the network would hold it twice (a crack).
//!
//! So after a build that met an exact zero sign, every vertex off the tet
//! corners is renamed by a rule that depends on the point alone: of the
//! functions vanishing (IA) or tied for the maximum (MI) there, the
//! lexicographically smallest set of the usual size that defines the point
//! (`sign(det A) != 0`, eq. 4). The choice is the same in every tet holding
//! the element:
//! - every such function is active in each of those tets (IA: a function of
//!   one strict sign at four corners keeps it in the whole tet; MI: a
//!   strictly dominated function is maximal nowhere), and active functions
//!   are numbered in ascending global order, so "smallest" agrees;
//! - `det A` and the zero tests read only the values at the element's
//!   corners, which all those tets share.
//!
//! A build with no zero sign needs no renaming: three planes through one
//! point meet there in some order, and the last one inserted finds the
//! vertex the first two made with sign 0 (or, for a plane through a whole
//! tet element, the element's corners with sign 0).

use smallvec::SmallVec;

use super::predicate::Predicates;
use super::types::{Complex, Vertex};

impl Complex {
    /// The functions (local ids, ascending) that vanish (IA) or are tied for
    /// the maximum (MI) at vertex `v` off the tet corners, its own included.
    pub(super) fn ties_at(&self, preds: &Predicates, v: usize) -> SmallVec<[u16; 8]> {
        let vert = &self.vertices[v];
        let own = vert.functions();
        let mut all: SmallVec<[u16; 8]> = own.iter().copied().collect();
        if self.degenerate {
            for f in 0..preds.values.len() as u16 {
                if !own.contains(&f) && preds.vertex_sign(vert, self.orient[v], f) == 0 {
                    all.push(f);
                }
            }
            all.sort_unstable();
        }
        all
    }

    /// [`Complex::ties_at`] for callers holding the build's `values`.
    pub(crate) fn tied_functions(&self, v: u32, values: &[[f64; 4]]) -> SmallVec<[u16; 8]> {
        let mode = self.mode.expect("a built complex");
        self.ties_at(&Predicates { values, mode, float: false }, v as usize)
    }

    /// Renames every vertex off the tet corners by its canonical functions
    /// (module docs); a no-op unless the build met a zero sign.
    pub(super) fn rename_tied_vertices(&mut self, preds: &Predicates) {
        if !self.degenerate {
            return;
        }
        for v in 0..self.vertices.len() {
            let vert = self.vertices[v];
            if vert.dim() == 0 {
                continue;
            }
            let all = self.ties_at(preds, v);
            if all.len() == vert.functions().len() {
                continue;
            }
            let (named, orient) = first_defining(preds, vert.simplex(), &all, vert.functions().len())
                .expect("the vertex's own functions define it");
            self.vertices[v] = named;
            self.orient[v] = orient;
        }
    }
}

/// The lexicographically first `n`-subset of `all` (ascending) that defines
/// a point on `simplex`, with its `sign(det A)`.
fn first_defining(preds: &Predicates, simplex: u8, all: &[u16], n: usize) -> Option<(Vertex, i8)> {
    let m = all.len();
    let mut pick: SmallVec<[usize; 4]> = (0..n).collect();
    loop {
        let funcs: SmallVec<[u16; 4]> = pick.iter().map(|&i| all[i]).collect();
        let v = Vertex::new(simplex, &funcs);
        let orient = preds.orient(&v);
        if orient != 0 {
            return Some((v, orient));
        }
        // Next combination in lexicographic order.
        let mut i = n;
        loop {
            if i == 0 {
                return None;
            }
            i -= 1;
            if pick[i] < m - n + i {
                break;
            }
        }
        pick[i] += 1;
        for j in i + 1..n {
            pick[j] = pick[j - 1] + 1;
        }
    }
}
