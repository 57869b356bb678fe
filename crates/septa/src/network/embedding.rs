//! What the certification of a result's written doubles found and changed
//! (`crate::mesh`): plain data, so every result type (grid networks, region
//! surfaces, label volumes) can carry it to the writers and front ends.
//!
//! The combinatorics of a network are exact; its coordinates are doubles.
//! The certificate is about those doubles as they are written, each polygon
//! fanned from its first vertex (what PLY, STL, trimesh and Python's
//! `Network.triangles` make of it): no two vertices at one point, no
//! triangle with collinear corners, no two triangles meeting except in
//! their shared vertices and edges, every cell of positive volume. Each
//! count is decided by exact signs on the doubles (`septa-exact`).

/// The exact check of written triangles: every count is exact.
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct EmbeddingCheck {
    /// Triangles checked (each polygon fanned from its first vertex).
    pub triangles: usize,
    /// Pairs of distinct vertices in use at the same point.
    pub coincident_points: usize,
    /// Triangles whose corners are collinear (a zero-length edge included).
    pub degenerate_triangles: usize,
    /// Pairs of triangles meeting anywhere besides their shared vertices and
    /// edges (degenerate triangles are left out of this test).
    pub intersecting_pairs: usize,
    /// Vertices in use with a coordinate that is not finite (nothing else is
    /// checked then).
    pub nonfinite_points: usize,
    /// Cells whose volume was checked: those bounded by the result's
    /// polygons (every edge used as often both ways) up to the grid's box.
    pub cells_checked: usize,
    /// Cells among them proven to have a positive volume: the flux of
    /// `(x_k - c) e_k`, with `c` one side of the box, through the cell's
    /// triangles is positive (the part of the cell's boundary on the box can
    /// only add to it), decided exactly. The others are cells for which no
    /// such flux is positive (a cell around the others that touches every
    /// side of the box): not a violation, not proven either.
    pub cells_positive: usize,
    /// The first offending elements, in words.
    pub examples: Vec<String>,
}

impl EmbeddingCheck {
    /// Violations: coincident points, degenerate triangles, intersecting
    /// pairs and non-finite points (0: the written triangles are an
    /// embedding of the network).
    pub fn violations(&self) -> usize {
        self.coincident_points + self.degenerate_triangles + self.intersecting_pairs + self.nonfinite_points
    }
}

/// What certification did to a result: the check before and after, and the
/// repairs, none of which changes a count of the network (vertices,
/// polygons, edges, patches, chains, corners, shells, cells).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Embedding {
    /// The check of the doubles as computed.
    pub before: EmbeddingCheck,
    /// The check of what is written (after the repairs).
    pub after: EmbeddingCheck,
    /// Vertices on the grid's box put exactly on its planes (their rounded
    /// position was off by an ulp or so).
    pub snapped: usize,
    /// Polygons fanned from another of their vertices (rotated loops: the
    /// same polygon, other triangles).
    pub rotated: usize,
    /// Vertices moved to repair the embedding (towards their neighbours,
    /// each move kept only when the exact check around it improved).
    pub nudged: usize,
    /// The largest move, relative to the length of the moved vertex's
    /// longest edge.
    pub largest_nudge: f64,
    /// Vertices moved onto the true surfaces, when projected (`None`: not
    /// asked for or not analytic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub projection: Option<Projection>,
    /// Seconds spent (also a stage, `certify`, of the result's seconds; not
    /// written here, so everything but `"seconds"` depends only on the input).
    #[serde(skip)]
    pub seconds: f64,
}

/// What the projection of vertices onto the true zero sets did.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct Projection {
    /// Vertices moved.
    pub moved: usize,
    /// Vertices left in place: the root finding did not converge inside the
    /// vertex's grid element, or the move would have broken the exact check.
    pub kept: usize,
    /// Of those, the ones kept because the exact check refused the move.
    pub kept_by_check: usize,
    /// The largest `|f| / |grad f|` over the vertices and their defining
    /// functions (MI: differences of functions) before.
    pub residual_before: f64,
    /// The same after.
    pub residual_after: f64,
}

/// The position `p` of the vertex with key `key` with each coordinate that
/// the exact vertex shares with its grid element (all the element's grid
/// vertices have it: a vertex on a grid edge parallel to x has that edge's y
/// and z) set to the grid's double, which interpolation can miss by an ulp.
/// Vertices on the box are then exactly on its planes. Every path that
/// writes a network (certified in memory, streamed) puts its points there.
pub fn snap_point(p: [f64; 3], key: &super::VKey, grid: &crate::grid::BoxGrid) -> [f64; 3] {
    let mut ijk = key.grid.iter().filter(|&&g| g != u32::MAX).map(|&g| grid.vertex_ijk(g));
    let Some(first) = ijk.next() else { return p };
    let mut same = [true; 3];
    for g in ijk {
        for k in 0..3 {
            same[k] &= g[k] == first[k];
        }
    }
    std::array::from_fn(|k| {
        if same[k] {
            crate::grid::grid_coordinate(grid.bounds[0][k], grid.bounds[1][k], first[k], grid.res[k])
        } else {
            p[k]
        }
    })
}
