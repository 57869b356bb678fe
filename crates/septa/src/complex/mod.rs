//! The convex cell complex of one tetrahedron (Du et al. 2022, Sec. 4-5).
//!
//! A tetrahedron `t` is partitioned by the zero sets of k linear functions
//! (implicit arrangement, **IA**) or by their upper envelope (material
//! interface, **MI**). Both partitions are convex, so they are built
//! incrementally, one function at a time, by bottom-up splitting of every
//! element (Sec. 4.1); MI follows each split by a merge (Sec. 4.2).
//!
//! ## Notation
//! - Tet vertices `0..4` are local; tet face `i` is the face opposite tet
//!   vertex `i` (the plane where barycentric coordinate `i` vanishes).
//! - Functions are *local* indices `0..k` into the caller's `values`
//!   array (the active functions of the tet, in the caller's order).
//! - A [`Vertex`] is never stored by coordinates: it is named by the tet
//!   element it lies on (a bit mask over tet vertices, `d + 1` bits for a
//!   `d`-simplex) and the functions whose planes meet there: `d` functions
//!   for IA, `d + 1` mutually equal functions for MI (Sec. 5.1).
//! - Every [`Face`] lies on one [`Plane`] and lists its vertices
//!   counter-clockwise seen from the plane's **positive side**; `cells[0]`
//!   is the cell on that side, `cells[1]` the one on the negative side
//!   ([`NONE`] outside the tet). The positive side of tet face `i` is the
//!   tet's interior; of `Function(i)` where `f_i > 0`; of `Pair(a, b)`
//!   (`a < b`) where `f_a > f_b`.
//!
//! ## Example
//! ```
//! use septa::complex::{Complex, Mode, Options};
//! // One function, zero on the plane x0 = 0.5 through the tet.
//! let values = [[-1.0, 1.0, 1.0, 1.0]];
//! let mut c = Complex::new();
//! c.build(Mode::Ia, &values, &Options::default()).unwrap();
//! assert_eq!(c.cells().len(), 2);
//! assert_eq!(c.network_faces().count(), 1);
//! c.check_invariants().unwrap();
//! ```

mod build;
mod canonical;
mod check;
mod coords;
mod dominated;
pub(crate) use coords::barycentric;
pub(crate) use dominated::WinnerSums;
mod lookup;
#[doc(hidden)]
#[cfg(feature = "tools")]
pub mod lookup_gen;
#[rustfmt::skip]
mod lookup_table;
mod merge;
mod predicate;
mod split;
#[cfg(feature = "tools")]
pub mod stress;
mod ties;
mod types;

pub use build::{BuildError, Options};
pub use canonical::CanonicalForm;
pub use types::{Cell, Complex, Edge, Face, Mode, Plane, Vertex, NONE};

/// `n` rows of corner values drawn from `pool` (unit tests of the
/// predicates and coordinates: small pools make zeros and ties common).
#[cfg(test)]
pub(crate) fn random_rows(rng: &mut impl rand::Rng, pool: &[f64], n: usize) -> Vec<[f64; 4]> {
    (0..n).map(|_| [0, 1, 2, 3].map(|_| pool[rng.gen_range(0..pool.len())])).collect()
}
