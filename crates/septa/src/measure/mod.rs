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

use crate::complex::NONE;
use crate::grid::BoxGrid;
use crate::network::Network;

/// The box a network was computed in: its resolution (for the exact test
/// of which vertices lie on its faces) and its corner `origin` with its
/// three edge vectors (a parallelepiped: a label volume placed by an affine
/// voxel-to-world map).
#[derive(Clone, Debug, PartialEq)]
pub struct BoxDomain {
    /// Cubes per axis.
    pub res: [usize; 3],
    /// World position of grid vertex `(0, 0, 0)`.
    pub origin: [f64; 3],
    /// World vector from `origin` to the last grid vertex along each axis.
    pub edges: [[f64; 3]; 3],
}

impl BoxDomain {
    /// The domain of a box grid.
    pub fn of_box(g: &BoxGrid) -> BoxDomain {
        let [lo, hi] = g.bounds;
        let mut edges = [[0.0; 3]; 3];
        for (a, e) in edges.iter_mut().enumerate() {
            e[a] = hi[a] - lo[a];
        }
        BoxDomain { res: g.res, origin: lo, edges }
    }

    /// This domain mapped by `x -> M x + t` (`affine` rows `[M | t]`).
    pub fn mapped(&self, affine: &[[f64; 4]; 3]) -> BoxDomain {
        let lin = |v: [f64; 3]| -> [f64; 3] {
            std::array::from_fn(|r| affine[r][0] * v[0] + affine[r][1] * v[1] + affine[r][2] * v[2])
        };
        let o = lin(self.origin);
        BoxDomain { res: self.res, origin: std::array::from_fn(|r| o[r] + affine[r][3]), edges: self.edges.map(lin) }
    }

    /// The domain's volume.
    pub fn volume(&self) -> f64 {
        dot(self.edges[0], cross(self.edges[1], self.edges[2])).abs()
    }

    /// Whether the domain is a mirror image of its grid (a voxel-to-world
    /// map with a negative determinant): every polygon's counter-clockwise
    /// side is then its negative side in space.
    pub fn mirrored(&self) -> bool {
        dot(self.edges[0], cross(self.edges[1], self.edges[2])) < 0.0
    }
}

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

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}
pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Twice the vector area of a planar polygon (Newell), pointing to the side
/// from which it is counter-clockwise: its positive side.
pub(crate) fn area_vector(points: &[[f64; 3]], poly: &[u32]) -> [f64; 3] {
    let p0 = points[poly[0] as usize];
    let mut n = [0.0; 3];
    for k in 1..poly.len() - 1 {
        let c = cross(sub(points[poly[k] as usize], p0), sub(points[poly[k + 1] as usize], p0));
        for i in 0..3 {
            n[i] += c[i];
        }
    }
    n
}

/// Area of a planar polygon.
pub fn polygon_area(points: &[[f64; 3]], poly: &[u32]) -> f64 {
    norm(area_vector(points, poly)) / 2.0
}

/// Twice the area of a planar polygon.
pub(crate) fn area_vector_len(points: &[[f64; 3]], poly: &[u32]) -> f64 {
    norm(area_vector(points, poly))
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

/// A polygon's cells as [the side its loop is counter-clockwise from in
/// space, the other]: swapped in a mirrored domain.
pub(crate) fn oriented(cells: [u32; 2], mirrored: bool) -> [u32; 2] {
    if mirrored {
        [cells[1], cells[0]]
    } else {
        cells
    }
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
