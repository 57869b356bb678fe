//! Why a cut was refused: every input problem names its element.

/// Why a cut was refused.
#[derive(Debug, thiserror::Error)]
pub enum CutError {
    /// No triangles.
    #[error("the mesh has no triangles")]
    EmptyMesh,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFiniteVertex {
        /// Vertex index (0-based).
        vertex: usize,
    },
    /// Two vertices at the same position.
    #[error("vertices {first} and {second} are at the same position (duplicate vertex)")]
    DuplicateVertex {
        /// First vertex.
        first: usize,
        /// Its duplicate.
        second: usize,
    },
    /// A triangle refers to a missing vertex.
    #[error("triangle {triangle} refers to a vertex that does not exist")]
    BadIndex {
        /// Triangle index.
        triangle: usize,
    },
    /// A triangle with collinear corners.
    #[error("triangle {triangle} is degenerate (zero area, exactly)")]
    DegenerateTriangle {
        /// Triangle index.
        triangle: usize,
    },
    /// An edge used more often in one direction than in the other.
    #[error("edge {a}->{b} is used in the same direction by triangles {other} and {triangle} ({forward} times a->b, {backward} times b->a): inconsistent orientation (flip the triangles facing the wrong way)")]
    NonManifoldOrFlipped {
        /// Triangles using the edge as `a -> b`.
        forward: usize,
        /// Triangles using it as `b -> a`.
        backward: usize,
        /// Triangle index.
        triangle: usize,
        /// The other triangle.
        other: usize,
        /// Edge start vertex.
        a: u32,
        /// Edge end vertex.
        b: u32,
    },
    /// An edge of four or more triangles, as many in each direction, whose
    /// orientations do not alternate around it (TopoCut App. C: consecutive
    /// triangles about the edge must bound one wedge of the domain between
    /// them): some points beside the edge would be inside the solid twice.
    #[error("edge {a}-{b} is non-manifold ({count} triangles, half in each direction) but triangles {first} and {second}, next to each other about the edge, face the same way: the solid would be inside itself there (a solid inside another sharing the edge with it, or flipped triangles); nested solids must face alternately (a cavity's triangles face inwards)")]
    EdgeWinding {
        /// Edge end (smaller index).
        a: u32,
        /// Edge end (larger index).
        b: u32,
        /// A triangle at the edge.
        first: usize,
        /// The next one about the edge, facing the same way.
        second: usize,
        /// Triangles around the edge.
        count: usize,
    },
    /// An edge with only one triangle.
    #[error("edge {a}->{b} of triangle {triangle} has no opposite triangle: the mesh is not watertight")]
    NotWatertight {
        /// Triangle index.
        triangle: usize,
        /// Edge start.
        a: u32,
        /// Edge end.
        b: u32,
    },
    /// Negative or zero signed volume.
    #[error("the mesh encloses signed volume {volume}: triangles must face outwards")]
    InwardOrientation {
        /// The signed volume.
        volume: f64,
    },
    /// Nested shells facing the same way (or a cavity facing outwards, or
    /// a lone shell facing inwards): some points would be inside the solid
    /// twice, or -1 times.
    #[error("shell {shell} (the triangles connected to triangle {triangle}) faces {facing} and lies inside shells {around:?}: the winding number would be {winding} next to it, but it must be 0 or 1 everywhere; nested shells must alternate orientation (the outermost faces outwards, a cavity's triangles face inwards): flip or remove shell {shell}")]
    ShellWinding {
        /// Shell index (shells are numbered by their smallest triangle).
        shell: usize,
        /// Its smallest triangle.
        triangle: usize,
        /// "outwards" (positive volume) or "inwards".
        facing: &'static str,
        /// The shells around it.
        around: Vec<usize>,
        /// A winding number other than 0 or 1 found beside the shell.
        winding: i64,
    },
    /// A shell encloses zero volume (exactly).
    #[error("shell {shell} (the triangles connected to triangle {triangle}) encloses zero volume")]
    FlatShell {
        /// Shell index.
        shell: usize,
        /// Its smallest triangle.
        triangle: usize,
    },
    /// A vertex of one shell lies on a triangle of another.
    #[error("vertex {vertex} lies on triangle {triangle} of another shell (the shells touch)")]
    ShellsTouch {
        /// The vertex.
        vertex: usize,
        /// The triangle.
        triangle: usize,
    },
    /// Two triangles meet away from their shared vertices.
    #[error("triangles {first} and {second} intersect (the mesh self-intersects)")]
    SelfIntersection {
        /// Smaller triangle index.
        first: usize,
        /// Larger triangle index.
        second: usize,
    },
    /// NaN or infinite plane coefficient.
    #[error("plane {plane} has a non-finite coefficient")]
    NonFinitePlane {
        /// Plane index.
        plane: usize,
    },
    /// `a = b = c = 0`.
    #[error("plane {plane} has a zero-length normal")]
    ZeroNormal {
        /// Plane index.
        plane: usize,
    },
    /// The input's magnitudes (or the memory it needs) are beyond what the
    /// cut handles; the message gives the range (`scale.rs`).
    #[error("{0}")]
    OutOfRange(String),
    /// The result failed a consistency check (a bug, reported not hidden).
    #[error("internal consistency check failed: {0}")]
    Inconsistent(String),
}
