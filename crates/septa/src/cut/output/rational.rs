//! Exact rational coordinates of cut-vertices, for users who need the
//! exact arrangement downstream (`septa cut --exact-vertices`). Each
//! cut-vertex is the intersection of the input elements named by its face
//! triple (TopoCut Sec. 3, eq. 2); its homogeneous coordinates
//! ([`Ctx::hom`], the same formulas every exact predicate of the cut uses)
//! are evaluated in big rationals from the input doubles and divided out,
//! so each coordinate is a reduced fraction `numerator / denominator`.

use crate::cut::base::geom::{Ctx, Def};
use crate::cut::input::input;
use crate::cut::CutError;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;
use rayon::prelude::*;
use septa_exact::Ring;

/// A big rational as a [`Ring`] (exact: every double is a dyadic rational).
#[derive(Clone, Debug, PartialEq)]
pub struct Rational(pub BigRational);

impl Ring for Rational {
    fn of(x: f64) -> Self {
        // finite inputs are checked before any cut; a non-finite one is 0 here
        Rational(BigRational::from_float(x).unwrap_or_else(BigRational::zero))
    }
    fn add(&self, o: &Self) -> Self {
        Rational(&self.0 + &o.0)
    }
    fn sub(&self, o: &Self) -> Self {
        Rational(&self.0 - &o.0)
    }
    fn mul(&self, o: &Self) -> Self {
        Rational(&self.0 * &o.0)
    }
    fn neg(&self) -> Self {
        Rational(-&self.0)
    }
}

/// The exact position of each cut-vertex of `defs` (as in
/// [`crate::cut::CutCellMesh::vertex_defs`]) over the input of the cut that made
/// them: `planes` are the planes the cut used ([`crate::cut::CutCellMesh::planes`],
/// duplicates dropped). Each coordinate is a reduced fraction with a
/// positive denominator.
pub fn exact_coordinates(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    planes: &[[f64; 4]],
    defs: &[Def],
) -> Result<Vec<[BigRational; 3]>, CutError> {
    let (edges, tri_edges, edge_tris) = input::check_mesh(vertices, triangles)?;
    let c = Ctx {
        verts: vertices,
        tris: triangles,
        planes,
        edges,
        tri_edges,
        edge_tris,
        wedges: Default::default(),
        pv: Vec::new(),
        tn_iv: Vec::new(),
        pp_iv: Vec::new(),
        tn_b: Vec::new(),
        pp_b: Vec::new(),
    };
    let out = defs
        .par_iter()
        .map(|&d| {
            let (h, w) = c.hom::<Rational>(d);
            // the three defining elements meet in one point: w != 0 (a
            // triple with w = 0 is never made a cut-vertex)
            let w = if w.0.is_zero() { BigRational::from_integer(BigInt::from(1)) } else { w.0 };
            h.map(|x| x.0 / &w)
        })
        .collect();
    Ok(out)
}

/// `numerator/denominator` (or just the numerator when the denominator is 1).
pub fn fraction_string(q: &BigRational) -> String {
    if q.denom() == &BigInt::from(1) {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}
