//! The cut-cell mesh a cut returns: cut-vertices (rounded, with their exact
//! face triples), cut-faces with the cells on their two sides, and what is
//! known of each cell (volume, exact volume sign, how each face is written).

use crate::cut::base::geom::Def;
use crate::cut::base::stats::{CutCounts, CutStats};
use septa_exact::Sign;

/// The input face a cut-face lies in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// Input triangle (outward normal).
    Tri(u32),
    /// Cut plane (its normal).
    Plane(u32),
}

/// One cut-face.
#[derive(Clone, Debug)]
pub struct CutFace {
    /// The input face it lies in.
    pub support: Support,
    /// Boundary loops of corner vertex ids: the outer boundary first,
    /// counter-clockwise about the support normal (triangle outward
    /// normal, or plane normal `(a, b, c)`), then holes (clockwise).
    pub loops: Vec<Vec<u32>>,
    /// Cell on the negative side (against the normal) and on the positive
    /// side; `u32::MAX` for none (outside the domain).
    pub cells: [u32; 2],
}

/// The cut-cell mesh.
#[derive(Clone, Debug, Default)]
pub struct CutCellMesh {
    /// Floating-point coordinates of the cut-vertices (nearest to exact up
    /// to rounding of the homogeneous coordinates).
    pub vertices: Vec<[f64; 3]>,
    /// Exact definition of each cut-vertex as a face triple.
    pub vertex_defs: Vec<Def>,
    /// Cut-faces.
    pub faces: Vec<CutFace>,
    /// Number of cut-cells; cell ids are `0..num_cells`.
    pub num_cells: usize,
    /// Counts.
    pub counts: CutCounts,
    /// Signed volume of the input mesh.
    pub mesh_volume: f64,
    /// The sum of the cell volumes and the mesh volume at the scale the cut
    /// ran at (`scale.rs`: the input times `2^k`): the same as the sum of
    /// `cell_volumes` and `mesh_volume` for inputs within `[2^-64, 2^64]`;
    /// for others those overflow or underflow (a cube of side 1e300 has
    /// volume 1e900), and [`CutCellMesh::validate`] compares these instead
    /// (the relative error does not change under scaling by `2^3k`).
    pub volume_sums_at_cut_scale: [f64; 2],
    /// The cut planes used (after dropping duplicates); `Support::Plane(p)`
    /// indexes this list.
    pub planes: Vec<[f64; 4]>,
    /// Outward normals of the input triangles (floating point, for output).
    pub tri_normals: Vec<[f64; 3]>,
    /// Twice the Euler characteristic of the domain: `V - E + T` of the
    /// input surface when it is a manifold, else that of the surface split
    /// at its non-manifold edges and pinched vertices, less twice what
    /// gluing them back removes (`input::NonManifold::domain_euler2`).
    pub mesh_euler: i64,
    /// Volume of each cell (from the floating-point embedding).
    pub cell_volumes: Vec<f64>,
    /// Exact sign of each cell's volume (from the cut-vertices' exact
    /// homogeneous coordinates; `volume.rs`): what [`CutCellMesh::validate`]
    /// checks, since a legitimate cell can be too small for `cell_volumes`.
    pub cell_volume_signs: Vec<Sign>,
    /// Per cut-face: written as triangles (no new vertices) instead of one
    /// polygon, because it has holes or its rounded vertices are not exactly
    /// coplanar ([`CutCellMesh::cell_polygons`]).
    pub face_split: Vec<bool>,
    /// Per cut-face: the triangles it is written as when split (vertex ids;
    /// ids from `vertex_defs.len()` on are face centres added by `repair.rs`,
    /// not cut-vertices), empty otherwise.
    pub face_triangles: Vec<Vec<[u32; 3]>>,
    /// Timings and predicate statistics.
    pub stats: CutStats,
}
