//! Measures of a result: the volume of every cell (so of every region or
//! label), the area of every patch (a region surface) and the length of
//! every chain (curve). Floating point, from the written coordinates; the
//! combinatorics they rest on (which polygons bound which cell, which
//! vertices lie on the grid's boundary) are the network's exact ones.
//!
//! A cell's volume is the divergence theorem over its boundary, `V = 1/3
//! \oint (x - O) . n dA`: its polygons, and where the cell reaches the
//! grid's boundary the part of the box surface it covers (its
//! *footprint*; `boundary.rs`). With `O` at the box's first corner the
//! three box faces through `O` add nothing, and each far face `F` adds
//! `d_F / 3` times the footprint's area, itself a line integral over the
//! network's edges in `F` and the box edges (Green's theorem, once per
//! dimension). So every cell of a box grid has a volume, whether it
//! touches the boundary or not, and the volumes sum to the box's.
//! On a tet mesh only the cells the network closes (every edge of their
//! polygons used an even number of times, and a positive volume inside)
//! have one; the others, which reach the mesh's boundary, are NaN.

mod boundary;
mod geometry;
mod solid;

pub use geometry::BoxDomain;
pub(crate) use geometry::{area_vector, area_vector_len, cross, dot, norm, oriented, sub};
pub use solid::{cell_solid, enclosed_volume, Solid, SolidError};

use crate::complex::NONE;
use crate::network::Network;

/// Volumes, areas and lengths of one result.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measures {
    /// Per cell (region, label, material cell), its volume; NaN where the
    /// cell is not closed by the network (tet meshes; module doc).
    pub cell_volume: Vec<f64>,
    /// Per patch (region surface), the area of its polygons.
    pub patch_area: Vec<f64>,
    /// Per chain (curve), its length.
    pub chain_length: Vec<f64>,
}

impl Measures {
    /// Whether nothing was measured (a result read back without them).
    pub fn is_empty(&self) -> bool {
        self.cell_volume.is_empty() && self.patch_area.is_empty() && self.chain_length.is_empty()
    }

    /// `{"cell_volume": [..], "patch_area": [..], "chain_length": [..]}`
    /// (a volume that is not known, NaN, as `null`).
    pub fn to_json(&self) -> serde_json::Value {
        let list = |xs: &[f64]| {
            serde_json::Value::Array(
                xs.iter().map(|&x| if x.is_finite() { x.into() } else { serde_json::Value::Null }).collect(),
            )
        };
        serde_json::json!({
            "cell_volume": list(&self.cell_volume),
            "patch_area": list(&self.patch_area),
            "chain_length": list(&self.chain_length),
        })
    }
}

/// Area of a planar polygon.
pub fn polygon_area(points: &[[f64; 3]], poly: &[u32]) -> f64 {
    norm(area_vector(points, poly)) / 2.0
}

/// Six times the signed volume of the cone from `o` over a polygon (its
/// triangle fan), positive when `o` is on its negative side.
fn cone6(points: &[[f64; 3]], poly: &[u32], o: [f64; 3]) -> f64 {
    let p0 = sub(points[poly[0] as usize], o);
    let mut v = 0.0;
    for k in 1..poly.len() - 1 {
        v += dot(p0, cross(sub(points[poly[k] as usize], o), sub(points[poly[k + 1] as usize], o)));
    }
    v
}

/// Length of a vertex path.
pub fn path_length(points: &[[f64; 3]], path: &[u32]) -> f64 {
    path.windows(2).map(|w| norm(sub(points[w[0] as usize], points[w[1] as usize]))).sum()
}

/// The measures of a network's cells, patches and chains; `domain` is the
/// box it was computed in (`None`: a tet mesh, module doc).
pub fn network_measures(net: &Network, domain: Option<&BoxDomain>) -> Measures {
    let points = &net.points;
    let mut patch_area = vec![0.0; net.patches.len()];
    for f in 0..net.num_faces() {
        if let Some(a) = patch_area.get_mut(net.face_patch[f] as usize) {
            *a += area_vector_len(points, net.face(f)) / 2.0;
        }
    }
    let chain_length = net.chains.iter().map(|c| path_length(points, c)).collect();
    Measures { cell_volume: cell_volumes(net, domain), patch_area, chain_length }
}

/// Every cell's volume (module doc).
fn cell_volumes(net: &Network, domain: Option<&BoxDomain>) -> Vec<f64> {
    let nc = net.cells.len();
    let points = &net.points;
    // The cone's apex: the box's first corner, else any point (the sum over
    // a closed cell does not depend on it; one near the network keeps the
    // terms small).
    let o = match domain {
        Some(d) => d.origin,
        None => points.first().copied().unwrap_or([0.0; 3]),
    };
    let mut six = vec![0.0; nc];
    let mirrored = domain.is_some_and(|d| d.mirrored());
    for f in 0..net.num_faces() {
        let [cp, cn] = oriented(net.face_cells[f], mirrored);
        // A polygon in the box's boundary (outside on one side) is part of
        // its cell's footprint there (`boundary.rs`), not counted twice.
        if domain.is_some() && (cp == NONE || cn == NONE) {
            continue;
        }
        let v = cone6(points, net.face(f), o);
        // Counter-clockwise from the positive side: the normal points into
        // the positive side's cell, out of the negative side's.
        if cn != NONE {
            six[cn as usize] += v;
        }
        if cp != NONE {
            six[cp as usize] -= v;
        }
    }
    let network_part: Vec<f64> = six.iter().map(|v| v / 6.0).collect();
    match domain {
        Some(d) => {
            let boundary = boundary::footprint_volumes(net, d, &network_part);
            network_part.iter().zip(boundary).map(|(a, b)| a + b).collect()
        }
        None => {
            let open = open_cells(net);
            // Closed by its polygons but enclosing a negative volume: the
            // cell outside them, which reaches the mesh's boundary.
            network_part.iter().zip(open).map(|(&v, open)| if open || v <= 0.0 { f64::NAN } else { v }).collect()
        }
    }
}

/// Cells whose polygons use some edge an odd number of times: not closed
/// by the network (they reach the boundary of a tet mesh).
fn open_cells(net: &Network) -> Vec<bool> {
    let mut uses: Vec<(u32, u32, u32)> = Vec::new();
    for f in 0..net.num_faces() {
        let p = net.face(f);
        for c in net.face_cells[f] {
            if c == NONE {
                continue;
            }
            for k in 0..p.len() {
                let (a, b) = (p[k], p[(k + 1) % p.len()]);
                uses.push((c, a.min(b), a.max(b)));
            }
        }
    }
    uses.sort_unstable();
    let mut open = vec![false; net.cells.len()];
    let mut i = 0;
    while i < uses.len() {
        let mut j = i;
        while j < uses.len() && uses[j] == uses[i] {
            j += 1;
        }
        if (j - i) % 2 == 1 {
            open[uses[i].0 as usize] = true;
        }
        i = j;
    }
    open
}
