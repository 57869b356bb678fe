//! The data of a per-tet cell complex: plane-based vertices, edges, faces, cells.

use smallvec::SmallVec;

/// "No element": a face's missing cell outside the tet, an unset index.
pub const NONE: u32 = u32::MAX;

/// Which partition of the tetrahedron is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Implicit arrangement: cut by the zero set of every function.
    Ia,
    /// Material interface: cut where the maximum changes hands.
    Mi,
}

/// A plane of the complex (Du et al. Sec. 5.1): a tet face, the zero set of
/// one function (IA), or the set where two functions are equal (MI).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Plane {
    /// Tet face `i`, opposite tet vertex `i`; positive side is the interior.
    TetFace(u8),
    /// `f_i = 0`; positive side is `f_i > 0`.
    Function(u16),
    /// `f_a = f_b` with `a < b`; positive side is `f_a > f_b`.
    Pair(u16, u16),
}

impl Plane {
    /// `Pair` with its functions in ascending order, and whether they were
    /// swapped (then the positive side of the result is the caller's negative side).
    pub fn pair(a: u16, b: u16) -> (Plane, bool) {
        if a < b {
            (Plane::Pair(a, b), false)
        } else {
            (Plane::Pair(b, a), true)
        }
    }

    /// True for the planes of the surface network (not tet faces).
    pub fn is_network(self) -> bool {
        !matches!(self, Plane::TetFace(_))
    }
}

/// A vertex, named by the planes that meet there, never by coordinates.
///
/// It lies in the relative interior of the tet element spanned by the tet
/// vertices in [`Vertex::simplex`] (a `d`-simplex, `d = popcount - 1`), on the
/// zero sets of its [`Vertex::functions`]: `d` of them for IA, `d + 1`
/// mutually equal ones for MI (for an MI tet corner: the material there).
/// Together with the tet faces opposite the missing tet vertices these are
/// the 3 planes that meet uniquely at the vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Vertex {
    simplex: u8,
    len: u8,
    funcs: [u16; 4],
}

impl Vertex {
    /// A vertex on the element `simplex` (bit mask over tet vertices) and the
    /// given functions (stored ascending).
    pub(crate) fn new(simplex: u8, functions: &[u16]) -> Vertex {
        debug_assert!(functions.len() <= 4 && simplex != 0 && simplex < 16);
        let mut funcs = [0u16; 4];
        funcs[..functions.len()].copy_from_slice(functions);
        funcs[..functions.len()].sort_unstable();
        Vertex { simplex, len: functions.len() as u8, funcs }
    }

    /// Bit mask over the tet vertices spanning the element the vertex lies on.
    pub fn simplex(&self) -> u8 {
        self.simplex
    }

    /// Dimension of that tet element: 0 corner, 1 edge, 2 face, 3 interior.
    pub fn dim(&self) -> usize {
        self.simplex.count_ones() as usize - 1
    }

    /// The defining functions (local indices), ascending.
    pub fn functions(&self) -> &[u16] {
        &self.funcs[..self.len as usize]
    }

    /// The tet vertices of [`Vertex::simplex`], ascending.
    pub fn tet_vertices(&self) -> SmallVec<[u8; 4]> {
        (0..4u8).filter(|i| self.simplex >> i & 1 == 1).collect()
    }

    pub(crate) fn set_functions(&mut self, functions: &[u16]) {
        *self = Vertex::new(self.simplex, functions);
    }
}

/// An edge between two vertices, on the intersection of two planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// End points.
    pub vertices: [u32; 2],
    /// The two planes whose intersection line holds the edge.
    pub planes: [Plane; 2],
}

/// A convex polygon of the complex on one plane.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Face {
    /// The plane the face lies on.
    pub plane: Plane,
    /// Vertex loop, counter-clockwise seen from the plane's positive side.
    pub vertices: SmallVec<[u32; 8]>,
    /// `edges[i]` joins `vertices[i]` and `vertices[i + 1]` (cyclically).
    pub edges: SmallVec<[u32; 8]>,
    /// `[cell on the positive side, cell on the negative side]`, [`NONE`] outside the tet.
    pub cells: [u32; 2],
}

/// A convex 3D cell of the complex.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cell {
    /// Bounding faces.
    pub faces: SmallVec<[u32; 8]>,
    /// IA: bit `i` set iff `f_i > 0` in the cell.
    pub(crate) positive: SmallVec<[u64; 2]>,
    /// MI: the function that is maximal in the cell.
    pub(crate) material: u16,
}

impl Cell {
    /// IA: whether function `f` (local index) is positive in the cell
    /// (it is never zero on a 3D cell).
    pub fn is_positive(&self, f: u16) -> bool {
        let (w, b) = (f as usize / 64, f % 64);
        self.positive.get(w).is_some_and(|x| x >> b & 1 == 1)
    }

    /// MI: the material (local function index) of the cell.
    pub fn material(&self) -> u16 {
        self.material
    }

    pub(crate) fn set_sign(&mut self, f: u16, positive: bool) {
        let (w, b) = (f as usize / 64, f % 64);
        if self.positive.len() <= w {
            self.positive.resize(w + 1, 0);
        }
        if positive {
            self.positive[w] |= 1 << b;
        } else {
            self.positive[w] &= !(1 << b);
        }
    }
}

/// The convex cell complex of one tetrahedron; see the [module docs](super).
///
/// Build it with [`Complex::build`]; a `Complex` is meant to be reused across
/// tetrahedra so that its buffers are allocated once.
#[derive(Clone, Debug, Default)]
pub struct Complex {
    pub(crate) mode: Option<Mode>,
    pub(crate) num_functions: usize,
    pub(crate) vertices: Vec<Vertex>,
    pub(crate) edges: Vec<Edge>,
    pub(crate) faces: Vec<Face>,
    pub(crate) cells: Vec<Cell>,
    /// Sign of det(A) (paper eq. 4) per vertex, cached at creation.
    pub(crate) orient: Vec<i8>,
    /// Scratch: sign of the function being inserted, per vertex.
    pub(crate) vsign: Vec<i8>,
    /// Whether the last build met an exact zero sign at a vertex, so that a
    /// vertex may lie on more planes than name it (complex/ties.rs).
    pub(crate) degenerate: bool,
    /// Scratch of the split and merge steps, kept to reuse its buffers.
    pub(crate) scratch: super::split::Scratch,
}

impl Complex {
    /// An empty complex; call [`Complex::build`].
    pub fn new() -> Complex {
        Complex::default()
    }

    /// The mode of the last build.
    pub fn mode(&self) -> Option<Mode> {
        self.mode
    }

    /// Number of functions of the last build.
    pub fn num_functions(&self) -> usize {
        self.num_functions
    }

    /// All vertices.
    pub fn vertices(&self) -> &[Vertex] {
        &self.vertices
    }

    /// All edges.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// All faces (on tet faces and on network planes).
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// All cells.
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// Ids of the faces of the surface network: those on a function plane
    /// (IA) or a function pair (MI), i.e. not on a tet face.
    ///
    /// A network plane that coincides with a tet face (a function vanishing
    /// on a whole tet face) splits nothing; such faces are on `TetFace`
    /// planes and are found by the caller from the input values.
    pub fn network_faces(&self) -> impl Iterator<Item = u32> + '_ {
        self.faces.iter().enumerate().filter(|(_, f)| f.plane.is_network()).map(|(i, _)| i as u32)
    }

    /// Vertices on the tet edge from tet vertex `a` to tet vertex `b`,
    /// ordered from `a` to `b`, both corners included.
    pub fn tet_edge_points(&self, a: u8, b: u8) -> SmallVec<[u32; 8]> {
        let mask = (1u8 << a) | (1u8 << b);
        let on = |v: u32| self.vertices[v as usize].simplex() & !mask == 0;
        let start = self.vertices.iter().position(|v| v.simplex() == 1 << a).map(|i| i as u32);
        let mut out = SmallVec::new();
        let Some(mut cur) = start else { return out };
        let mut prev = NONE;
        out.push(cur);
        loop {
            let next = self.edges.iter().find_map(|e| {
                let [p, q] = e.vertices;
                if p == cur && q != prev && on(q) {
                    Some(q)
                } else if q == cur && p != prev && on(p) {
                    Some(p)
                } else {
                    None
                }
            });
            match next {
                Some(n) => {
                    prev = cur;
                    cur = n;
                    out.push(cur);
                    if self.vertices[cur as usize].simplex() == 1 << b {
                        break;
                    }
                }
                None => break,
            }
        }
        out
    }
}
