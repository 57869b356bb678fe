//! Building a complex: the initial tetrahedron and one update per function.

use smallvec::smallvec;

use super::predicate::Predicates;
use super::split::Scratch;
use super::types::{Cell, Complex, Edge, Face, Mode, Plane, Vertex, NONE};

/// Options of [`Complex::build`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Options {
    /// Use naive floating-point signs instead of the exact predicate.
    /// Only for measuring what exactness buys (`septa stress --float`).
    /// Default value: `false`.
    pub float: bool,
    /// Use the look-up tables for IA with 1-2 functions and MI with 2-3
    /// (Sec. 6); they give the same complex as the incremental
    /// construction; with `float` their branch predicates are naive too. Default value: `true`.
    pub lookup: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options { float: false, lookup: true }
    }
}

impl Options {
    /// Options with the naive floating-point predicate switched on or off.
    pub fn with_float(float: bool) -> Options {
        Options { float, ..Options::default() }
    }

    /// Options with the look-up tables switched on or off.
    pub fn with_lookup(lookup: bool) -> Options {
        Options { lookup, ..Options::default() }
    }
}

/// Why a complex could not be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BuildError {
    /// An input value is NaN or infinite.
    #[error("value {value} of function {function} at tet vertex {vertex} is not finite")]
    NonFinite {
        /// Local function index.
        function: usize,
        /// Tet vertex (0..4).
        vertex: usize,
        /// The offending value.
        value: f64,
    },
    /// More functions than the complex can index.
    #[error("{count} functions in one tetrahedron; at most 65535 are supported")]
    TooManyFunctions {
        /// The number given.
        count: usize,
    },
    /// A material interface needs at least one function.
    #[error("a material interface needs at least one function")]
    NoFunctions,
    /// The signs asked for an impossible split. Cannot happen with exact
    /// signs; with `Options::float` it is the paper's Type II failure.
    #[error("inconsistent signs while inserting function {function} ({element} split)")]
    Ambiguous {
        /// Local index of the function being inserted.
        function: usize,
        /// Which kind of element could not be split.
        element: &'static str,
    },
}

/// Loops of the four tet faces, counter-clockwise seen from inside
/// (for a positively oriented tet, `det[v1-v0, v2-v0, v3-v0] > 0`).
const TET_FACES: [[u32; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];
/// The six tet edges.
const TET_EDGES: [[u32; 2]; 6] = [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]];
/// Edges of each loop in `TET_FACES`: `TET_FACE_EDGES[t][i]` joins corners `i` and `i + 1`.
const TET_FACE_EDGES: [[u32; 3]; 4] = [[4, 5, 3], [1, 5, 2], [2, 4, 0], [0, 3, 1]];
/// Planes of each edge in `TET_EDGES`: the tet faces opposite the other two corners.
const TET_EDGE_PLANES: [[u8; 2]; 6] = [[2, 3], [1, 3], [1, 2], [0, 3], [0, 2], [0, 1]];

impl Complex {
    /// Builds the IA or MI of the functions whose values at the 4 tet
    /// vertices are `values[i]` (row `i` = function `i`), inside a
    /// positively oriented tetrahedron.
    ///
    /// Functions are inserted in the given order; the result does not
    /// depend on it (up to numbering), since every sign is exact.
    pub fn build(&mut self, mode: Mode, values: &[[f64; 4]], options: &Options) -> Result<(), BuildError> {
        let mut scratch = std::mem::take(&mut self.scratch);
        let result = self.build_with(mode, values, options, &mut scratch);
        self.scratch = scratch;
        result
    }

    /// Which look-up table template [`Complex::build`] would decode for
    /// these values, as a key unique over all tables (table number in the
    /// high word, template offset in the low word); `None` when it would run
    /// the incremental construction. Two inputs with the same key get the
    /// same complex, numbering included.
    pub(crate) fn template_key(mode: Mode, values: &[[f64; 4]], options: &Options) -> Option<u64> {
        if !options.lookup || values.iter().flatten().any(|v| !v.is_finite()) {
            return None;
        }
        let table = super::lookup::table(mode, values.len())?;
        let preds = Predicates { values, mode, float: options.float };
        let t = super::lookup::find(table, &preds, values.len())?;
        let id: u64 = match (mode, values.len()) {
            (Mode::Ia, k) => k as u64,
            (Mode::Mi, k) => 8 + k as u64,
        };
        Some(id << 32 | t as u64)
    }

    /// [`Complex::build`] with caller-owned scratch space (no allocation
    /// once the buffers have grown).
    pub(crate) fn build_with(
        &mut self,
        mode: Mode,
        values: &[[f64; 4]],
        options: &Options,
        scratch: &mut Scratch,
    ) -> Result<(), BuildError> {
        for (function, row) in values.iter().enumerate() {
            if let Some(vertex) = row.iter().position(|v| !v.is_finite()) {
                return Err(BuildError::NonFinite { function, vertex, value: row[vertex] });
            }
        }
        if values.len() > u16::MAX as usize {
            return Err(BuildError::TooManyFunctions { count: values.len() });
        }
        if mode == Mode::Mi && values.is_empty() {
            return Err(BuildError::NoFunctions);
        }
        self.mode = Some(mode);
        self.num_functions = values.len();
        self.degenerate = false;
        let preds = Predicates { values, mode, float: options.float };
        if options.lookup {
            if let Some(table) = super::lookup::table(mode, values.len()) {
                if let Some(t) = super::lookup::find(table, &preds, values.len()) {
                    self.decode(&table.data[t as usize..]);
                    return Ok(());
                }
            }
        }
        let first = match self.decode_prefix(&preds, options) {
            Some(inserted) => inserted,
            None => {
                self.init_tet(0);
                if mode == Mode::Mi {
                    1
                } else {
                    0
                }
            }
        };
        for f in first..values.len() as u16 {
            self.insert(&preds, f, scratch)?;
        }
        self.rename_tied_vertices(&preds);
        Ok(())
    }

    /// For more functions than any table holds: the complex of the first
    /// `p` functions decoded from the largest table (IA `p = 2`, MI `p = 3`),
    /// with each vertex's orientation, and `p`, the number of functions
    /// inserted; `None` when that prefix falls back (a zero sign).
    ///
    /// The incremental construction inserts functions in order and its
    /// state after `p` of them depends on nothing else, so continuing from
    /// the decoded prefix gives the same complex, numbering included, as
    /// inserting every function: a table template *is* that state
    /// (module docs of `lookup`), and a template is only found when every
    /// sign the prefix reads is non-zero, as `degenerate = false` says.
    /// The orientations are recomputed because templates do not hold them
    /// (a table user never signs another function at its vertices).
    fn decode_prefix(&mut self, preds: &Predicates, options: &Options) -> Option<u16> {
        let p = match preds.mode {
            Mode::Ia => 2,
            Mode::Mi => 3,
        };
        if !options.lookup || preds.values.len() <= p {
            return None;
        }
        let prefix = Predicates { values: &preds.values[..p], mode: preds.mode, float: preds.float };
        let table = super::lookup::table(preds.mode, p)?;
        let t = super::lookup::find(table, &prefix, p)?;
        self.decode(&table.data[t as usize..]);
        for v in 0..self.vertices.len() {
            self.orient[v] = preds.orient(&self.vertices[v]);
        }
        Some(p as u16)
    }

    /// Resets to the bare tetrahedron (one cell; MI material `material`).
    fn init_tet(&mut self, material: u16) {
        self.vertices.clear();
        self.orient.clear();
        let mi = self.mode == Some(Mode::Mi);
        for i in 0..4u8 {
            let funcs: &[u16] = if mi { &[material] } else { &[] };
            self.vertices.push(Vertex::new(1 << i, funcs));
            self.orient.push(1);
        }
        self.edges.clear();
        for (e, [p, q]) in TET_EDGES.iter().zip(TET_EDGE_PLANES) {
            self.edges.push(Edge { vertices: *e, planes: [Plane::TetFace(p), Plane::TetFace(q)] });
        }
        self.faces.clear();
        for (t, tri) in TET_FACES.iter().enumerate() {
            self.faces.push(Face {
                plane: Plane::TetFace(t as u8),
                vertices: tri.iter().copied().collect(),
                edges: TET_FACE_EDGES[t].iter().copied().collect(),
                cells: [0, NONE],
            });
        }
        self.cells.clear();
        self.cells.push(Cell { faces: smallvec![0, 1, 2, 3], positive: smallvec![], material });
    }

    /// Inserts function `f` (Sec. 4.1 for IA, 4.2 for MI).
    fn insert(&mut self, preds: &Predicates, f: u16, scratch: &mut Scratch) -> Result<(), BuildError> {
        self.vsign.clear();
        let (mut pos, mut neg) = (false, false);
        for v in 0..self.vertices.len() {
            let s = preds.vertex_sign(&self.vertices[v], self.orient[v], f);
            pos |= s > 0;
            neg |= s < 0;
            self.degenerate |= s == 0;
            self.vsign.push(s);
        }
        match preds.mode {
            Mode::Ia => {
                if !(pos && neg) {
                    for cell in &mut self.cells {
                        cell.set_sign(f, pos);
                    }
                    return Ok(());
                }
                self.split(preds, f, scratch)
            }
            Mode::Mi => {
                if !neg {
                    return Ok(()); // f never strictly wins: the MI is unchanged
                }
                if !pos {
                    self.init_tet(f); // f wins everywhere
                    return Ok(());
                }
                self.split(preds, f, scratch)?;
                self.merge(f, scratch);
                Ok(())
            }
        }
    }
}
