//! One job model for every front end: what to partition (a grid and
//! functions), read once from whatever the user has (an `.npz` of samples,
//! a reference config or function list, a scene file in JSON or TOML, a
//! built-in scene, or the job JSON of the distributed path), and run on the
//! path that applies: sparse evaluation for formulas on a box grid, the
//! dense path for samples or a tet mesh. The command line, Python and Dask
//! all build a [`Job`] here, so a function means the same on every path
//! (a plane's normal is normalised wherever it is read: one reader and one
//! evaluator per primitive, `scene/`).
//!
//! ```
//! use septa::job::{GridOverride, Job};
//! use septa::network::NetworkOptions;
//! use septa::complex::Mode;
//! let job = Job::load("builtin:sphere-with-hole", &GridOverride { resolution: Some(8), ..Default::default() }).unwrap();
//! let (net, sparse) = job.run(&NetworkOptions::new(job.mode.unwrap_or(Mode::Ia)), false).unwrap();
//! assert!(sparse.is_some() && net.num_faces() > 0);
//! ```

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::complex::Mode;
use crate::grid::{BoxGrid, Grid, Split, TetMesh};
use crate::network::{compute, compute_sparse, Network, NetworkError, NetworkOptions, SparseStats};
use crate::scene::{load_function_list, sample_grid, Primitive, Scene, SceneError};

/// The functions of a job.
#[derive(Clone, Debug)]
pub enum Functions {
    /// Formulas, evaluated where needed (sparse evaluation applies on a box grid).
    Formulas(Vec<Primitive>),
    /// Values at the grid vertices, `values[v * k + f]`.
    Samples {
        /// The values.
        values: Vec<f64>,
        /// Number of functions.
        k: usize,
    },
}

/// What to partition.
#[derive(Clone, Debug)]
pub struct Job {
    /// The tet grid.
    pub grid: Grid,
    /// The functions.
    pub functions: Functions,
    /// The mode a scene asks for (`None`: the caller decides).
    pub mode: Option<Mode>,
    /// The scene, when the job came from one (region rules, names).
    pub scene: Option<Scene>,
}

/// Grid settings given beside the input (command-line flags, Python
/// arguments); each one given replaces the file's own setting.
#[derive(Clone, Debug, Default)]
pub struct GridOverride {
    /// Cubes per axis.
    pub resolution: Option<usize>,
    /// Min and max corner.
    pub bounds: Option<[[f64; 3]; 2]>,
    /// Tets per cube.
    pub split: Option<Split>,
    /// A tet mesh (Gmsh `.msh` or the reference's tet-mesh `.json`) instead of a box.
    pub mesh: Option<PathBuf>,
}

/// Why a job could not be read.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// A file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// A scene, config or function list is wrong (file, line, field).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// An `.npz` is wrong.
    #[error(transparent)]
    Npz(#[from] crate::io::NpzError),
    /// A Gmsh file is wrong.
    #[error(transparent)]
    Msh(#[from] crate::io::MshError),
    /// A reference tet-mesh JSON is wrong.
    #[error(transparent)]
    Reference(#[from] crate::io::RefError),
    /// Anything else about the input, naming the file and what is wrong.
    #[error("{file}: {message}")]
    Input {
        /// The file (or `<job>`).
        file: String,
        /// What is wrong.
        message: String,
    },
}

fn input(file: &str, message: impl Into<String>) -> JobError {
    JobError::Input { file: file.to_string(), message: message.into() }
}

/// A file's value tree: JSON, or TOML (`.toml`) read into the same tree.
fn value_of(text: &str, path: &Path) -> Result<Value, JobError> {
    let name = path.display().to_string();
    if path.extension().and_then(|e| e.to_str()) == Some("toml") {
        let v: toml::Value = toml::from_str(text).map_err(|e| input(&name, format!("not TOML: {e}")))?;
        return serde_json::to_value(v).map_err(|e| input(&name, e.to_string()));
    }
    // FILE:LINE:COLUMN, as every scene error is written
    crate::scene::parse_json_strict(text)
        .map_err(|e| input(&format!("{name}:{}:{}", e.line(), e.column()), format!("not JSON: {e}")))
}

fn read_text(path: &Path) -> Result<String, JobError> {
    crate::io::read_input_text(path).map_err(|source| JobError::Io { path: path.display().to_string(), source })
}

/// A box grid of `n^3` cubes over `bounds` (default `[-1, 1]^3`, 5 tets per cube).
fn cube_grid(file: &str, n: usize, over: &GridOverride) -> Result<BoxGrid, JobError> {
    let bounds = over.bounds.unwrap_or([[-1.0; 3], [1.0; 3]]);
    BoxGrid::new([n; 3], bounds, over.split.unwrap_or(Split::Five)).map_err(|e| input(file, e.to_string()))
}

/// Reads a tet mesh file (`.msh`, or the reference's tet-mesh `.json`).
fn read_tet_mesh(path: &Path) -> Result<TetMesh, JobError> {
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let (vertices, tets) = if ext == "msh" { crate::io::read_msh(path)? } else { crate::io::read_tet_mesh_json(path)? };
    TetMesh::new(vertices, &tets).map_err(|e| input(&path.display().to_string(), e.to_string()))
}

impl Job {
    /// Reads a job from `input`: a path (`.npz`, `.json`, `.toml`) or
    /// `builtin:NAME`, with the grid settings `over` given beside it.
    pub fn load(input_path: &str, over: &GridOverride) -> Result<Job, JobError> {
        if input_path.starts_with("builtin:") {
            return Job::from_scene(Scene::load(input_path)?, over);
        }
        let path = Path::new(input_path);
        if path.extension().and_then(|e| e.to_str()) == Some("npz") {
            return Job::from_npz(path);
        }
        let text = read_text(path)?;
        let v = value_of(&text, path)?;
        let base = path.parent();
        if v.get("funcFile").is_some() && v.get("tetMeshFile").is_some() {
            // A reference config on a tet mesh: formulas sampled at its vertices.
            let dir = base.unwrap_or(Path::new("."));
            let file = |k: &str| dir.join(v[k].as_str().unwrap_or_default());
            let f = file("funcFile");
            let functions = load_function_list(&read_text(&f)?, &f.display().to_string(), f.parent())?;
            let mesh = read_tet_mesh(&file("tetMeshFile"))?;
            return Ok(Job::on_mesh(mesh, functions));
        }
        if v.is_object() && v.get("input").is_none() {
            // A scene or a reference config on a box grid, from the text
            // read once (a pipe, `/dev/stdin`, cannot be read twice).
            let scene = if path.extension().and_then(|e| e.to_str()) == Some("toml") {
                Scene::from_toml(&text, input_path, base)?
            } else {
                Scene::from_json(&text, input_path, base)?
            };
            return Job::from_scene(scene, over);
        }
        // A function list.
        let functions = load_function_list(&text, input_path, base)?;
        if let Some(mesh) = &over.mesh {
            return Ok(Job::on_mesh(read_tet_mesh(mesh)?, functions));
        }
        let n = over.resolution.ok_or_else(|| {
            input(input_path, "a function list needs a grid: --grid N (and optionally --bounds) or --mesh FILE")
        })?;
        let grid = cube_grid(input_path, n, over)?;
        Ok(Job { grid: Grid::Box(grid), functions: Functions::Formulas(functions), mode: None, scene: None })
    }

    /// A scene's job; `over.resolution`, `over.bounds` and `over.split`
    /// replace the scene's grid settings when given.
    pub fn from_scene(mut scene: Scene, over: &GridOverride) -> Result<Job, JobError> {
        let file = "<scene>";
        if let Some(n) = over.resolution {
            scene.grid.resolution = [n; 3];
        }
        if let Some(b) = over.bounds {
            scene.grid.bounds = b;
        }
        if let Some(s) = over.split {
            scene.grid.split = s.tets_per_cube() as u8;
        }
        if let Some(mesh) = &over.mesh {
            let mesh = read_tet_mesh(mesh)?;
            let mut job = Job::on_mesh(mesh, scene.functions.clone());
            job.mode = Some(scene.mode);
            job.scene = Some(scene);
            return Ok(job);
        }
        let grid = scene.grid.box_grid().map_err(|e| input(file, e.to_string()))?;
        Ok(Job {
            grid: Grid::Box(grid),
            functions: Functions::Formulas(scene.functions.clone()),
            mode: Some(scene.mode),
            scene: Some(scene),
        })
    }

    /// Formulas on a tet mesh (sampled at its vertices when run).
    fn on_mesh(mesh: TetMesh, functions: Vec<Primitive>) -> Job {
        Job { grid: Grid::Mesh(mesh), functions: Functions::Formulas(functions), mode: None, scene: None }
    }

    /// An `.npz` of samples (`vertices`, `tets`, `values`): a reference box
    /// grid when `grid_res` and `bbox` describe exactly the stored tets,
    /// a tet mesh otherwise.
    fn from_npz(path: &Path) -> Result<Job, JobError> {
        let data = crate::io::read_grid_input(path)?;
        let samples = |values, k| Functions::Samples { values, k };
        if let (Some(r), Some(bbox)) = (data.grid_res, data.bbox) {
            if let Ok(g) = BoxGrid::new([r; 3], bbox, Split::Five) {
                let grid = Grid::Box(g);
                let same = grid.num_tets() == data.tets.len()
                    && grid.num_vertices() == data.vertices.len()
                    && data.tets.iter().enumerate().all(|(t, tet)| grid.tet(t).map(|v| v as i64) == *tet);
                if same {
                    return Ok(Job { grid, functions: samples(data.values, data.k), mode: None, scene: None });
                }
            }
        }
        let mesh =
            TetMesh::new(data.vertices, &data.tets).map_err(|e| input(&path.display().to_string(), e.to_string()))?;
        Ok(Job { grid: Grid::Mesh(mesh), functions: samples(data.values, data.k), mode: None, scene: None })
    }

    /// The job JSON of the distributed path: `{"mode": "ia"|"mi", "block":
    /// 16, "grid": {"resolution": n or [nx, ny, nz], "bounds": [[..], [..]],
    /// "split": 5|6}, "functions": [..]}` or `{"scene": {..} or
    /// "builtin:NAME", ..}` (mode and grid from the scene unless given);
    /// `"base_dir"` resolves relative paths. Returns the job and the block
    /// edge it asks for.
    pub fn from_job_json(text: &str) -> Result<(Job, Option<usize>), JobError> {
        let file = "<job>";
        let v: Value = crate::scene::parse_json_strict(text).map_err(|e| input(file, format!("not JSON: {e}")))?;
        let base = v.get("base_dir").and_then(Value::as_str).map(PathBuf::from);
        let mut job = match (v.get("scene"), v.get("functions")) {
            (Some(s), None) => {
                let scene = match s {
                    Value::String(name) => Scene::load(name)?,
                    _ => Scene::from_json(&s.to_string(), "<scene>", base.as_deref())?,
                };
                Job::from_scene(scene, &GridOverride::default())?
            }
            (None, Some(f)) => {
                let fs = load_function_list(&f.to_string(), "<functions>", base.as_deref())?;
                let g = v.get("grid").ok_or_else(|| input(file, "a list of functions needs \"grid\""))?;
                Job { grid: Grid::Box(grid_of(g)?), functions: Functions::Formulas(fs), mode: None, scene: None }
            }
            _ => return Err(input(file, "give exactly one of \"scene\" and \"functions\"")),
        };
        if let (Some(g), Some(_)) = (v.get("grid"), v.get("scene")) {
            job.grid = Grid::Box(grid_of(g)?);
        }
        match v.get("mode").and_then(Value::as_str) {
            Some("ia") => job.mode = Some(Mode::Ia),
            Some("mi") => job.mode = Some(Mode::Mi),
            Some(m) => return Err(input(file, format!("mode must be \"ia\" or \"mi\", not {m:?}"))),
            None => {}
        }
        let block = match v.get("block") {
            None => None,
            Some(b) => {
                Some(b.as_u64().filter(|&b| b >= 1).ok_or_else(|| input(file, "block: expected a positive integer"))?
                    as usize)
            }
        };
        Ok((job, block))
    }

    /// Number of functions.
    pub fn k(&self) -> usize {
        match &self.functions {
            Functions::Formulas(f) => f.len(),
            Functions::Samples { k, .. } => *k,
        }
    }

    /// The box grid and formulas, when sparse evaluation applies.
    pub fn box_formulas(&self) -> Option<(&BoxGrid, &[Primitive])> {
        match (&self.grid, &self.functions) {
            (Grid::Box(g), Functions::Formulas(f)) => Some((g, f)),
            _ => None,
        }
    }

    /// The values at every grid vertex (`values[v * k + f]`): the samples,
    /// or the formulas evaluated at every vertex (the dense path).
    pub fn values(&self) -> std::borrow::Cow<'_, [f64]> {
        match &self.functions {
            Functions::Samples { values, .. } => values.as_slice().into(),
            Functions::Formulas(f) => sample_grid(f, &self.grid.vertices()).into(),
        }
    }

    /// Computes the network: sparsely where it applies (unless `dense`),
    /// on every vertex otherwise; the output is identical either way. The
    /// sparse path's statistics come back when it ran.
    pub fn run(&self, options: &NetworkOptions, dense: bool) -> Result<(Network, Option<SparseStats>), NetworkError> {
        match self.box_formulas() {
            Some((g, f)) if !dense => compute_sparse(g, f, options).map(|(n, s)| (n, Some(s))),
            _ => {
                if let Some((g, f)) = self.box_formulas() {
                    // Estimated before sampling every vertex (before: `--grid 1000 --dense`).
                    crate::grid::memory::check_dense(g.num_vertices(), f.len(), DENSE_WAY_OUT)?;
                }
                compute(&self.grid, &self.values(), self.k(), options).map(|n| (n, None))
            }
        }
    }
}

/// The way out of a dense job too large for memory.
const DENSE_WAY_OUT: &str = "drop --dense (the default sparse path samples only blocks near the surfaces; --stream OUT.ply also bounds the output's memory) or use a coarser --grid";

/// The `"grid"` object of a job JSON.
fn grid_of(v: &Value) -> Result<BoxGrid, JobError> {
    let file = "<job>";
    let res = match v.get("resolution") {
        Some(Value::Array(a)) if a.len() == 3 => {
            let mut r = [0; 3];
            for (i, x) in a.iter().enumerate() {
                r[i] = x.as_u64().ok_or_else(|| input(file, "grid.resolution: expected positive integers"))? as usize;
            }
            r
        }
        Some(x) => [x.as_u64().ok_or_else(|| input(file, "grid.resolution: expected n or [nx, ny, nz]"))? as usize; 3],
        None => return Err(input(file, "grid.resolution: missing")),
    };
    let bounds = match v.get("bounds") {
        None => [[-1.0; 3], [1.0; 3]],
        Some(b) => serde_json::from_value(b.clone())
            .map_err(|_| input(file, "grid.bounds: expected [[x0, y0, z0], [x1, y1, z1]]"))?,
    };
    let split = match v.get("split").and_then(Value::as_u64).unwrap_or(5) {
        s @ (5 | 6) => Split::try_from(s as u8).map_err(|e| input(file, e.to_string()))?,
        s => return Err(input(file, format!("grid.split: must be 5 or 6, not {s}"))),
    };
    BoxGrid::new(res, bounds, split).map_err(|m| input(file, format!("grid: {m}")))
}
