//! `--adaptive` for `septa ia|mi|regions`: the grid refined until the
//! network of the true functions is certified (docs/adaptive.md), then
//! the exact extraction on it, and `grid.vtu` + `adaptive.json` beside the
//! result.
use std::time::Instant;

use septa::adaptive::{adaptive_json, grid_vtu, refine_with_progress, AdaptiveGrid, AdaptiveOptions, Stop};
use septa::complex::Mode;
use septa::grid::Grid;
use septa::job::{Functions, Job};

/// The adaptive flags (shared by ia, mi and regions).
#[derive(clap::Args, Clone, Debug, Default)]
pub struct AdaptiveArgs {
    /// Refine the grid until the network of the true functions is
    /// certified (docs/adaptive.md): start from a coarse box grid, bisect
    /// tets until each is proven to hold the functions' zero sets as the
    /// linear interpolants' (sheets, curves, points) within --tolerance,
    /// then extract exactly. Writes grid.vtu (the tets, with why each
    /// stopped) and adaptive.json. For analytic functions (a scene or a
    /// function list).
    #[arg(long)]
    pub adaptive: bool,
    /// With --adaptive: distance bound between the true and the extracted
    /// surfaces and curves, in scene units (default: 1e-3 of the box's
    /// longest side).
    #[arg(long, requires = "adaptive", value_parser = crate::args::finite)]
    pub tolerance: Option<f64>,
    /// With --adaptive: the most tets the grid may have (default 4000000);
    /// leaves left uncertified when it is reached are reported.
    #[arg(long, requires = "adaptive")]
    pub max_tets: Option<usize>,
    /// With --adaptive: leaves this short stop uncertified and are reported
    /// (default: 1/65536 of the box's longest side).
    #[arg(long, requires = "adaptive", value_parser = crate::args::finite)]
    pub min_edge: Option<f64>,
    /// With --adaptive: start cubes along the box's longest side (default 4).
    #[arg(long, requires = "adaptive")]
    pub start_cubes: Option<usize>,
}

/// The refined grid and how long it took.
pub struct Refined {
    /// The grid.
    pub grid: AdaptiveGrid,
    /// Seconds spent refining.
    pub seconds: f64,
}

impl Refined {
    /// The files written beside the result.
    pub fn files(&self) -> (Vec<u8>, Vec<u8>) {
        let json = serde_json::to_vec_pretty(&adaptive_json(&self.grid, self.seconds)).expect("json");
        (grid_vtu(&self.grid), json)
    }

    /// The summary object for `--json`.
    pub fn json(&self) -> serde_json::Value {
        let mut v = adaptive_json(&self.grid, self.seconds);
        v.as_object_mut().map(|o| o.remove("uncertified_places"));
        v
    }

    /// Lines for the text summary; the uncertified leaves are never silent.
    pub fn text(&self) -> String {
        let g = &self.grid;
        let (short, _) = g.edge_range();
        let mut s = format!(
            "adaptive grid: {} tets, {} vertices, {} rounds, {:.3} s; leaves certified {}, empty {}, min-edge {}, budget {}; shortest edge {:.3e}, worst radius ratio {:.3}\n",
            g.tets.len(),
            g.vertices.len(),
            g.rounds,
            self.seconds,
            g.count(Stop::Certified),
            g.count(Stop::Empty),
            g.count(Stop::MinEdge),
            g.count(Stop::Budget),
            short,
            g.worst_radius_ratio()
        );
        let places = g.uncertified_places();
        if places.is_empty() {
            s += &format!("certified: every leaf proven (tolerance {:.3e})\n", g.options.tolerance);
        } else {
            s += &format!(
                "NOT certified at {} leaves (--min-edge {:.3e} or --max-tets {} reached); adaptive.json lists them, grid.vtu shows them (stop 2, 3); first at {:?}\n",
                places.len(),
                g.options.min_edge,
                g.options.max_tets,
                places[0]
            );
        }
        s
    }
}

/// Replaces the job's box grid by a certified adaptive grid over the same
/// box. Errors name the flag.
pub fn apply(args: &AdaptiveArgs, job: &mut Job, mode: Mode, quiet: bool) -> Result<Refined, String> {
    let (bounds, functions) = match (&job.grid, &job.functions) {
        (Grid::Box(b), Functions::Formulas(f)) => (b.bounds, f.clone()),
        _ => return Err(
            "--adaptive: the input must be analytic functions (a scene or a function list), not samples or a tet mesh"
                .into(),
        ),
    };
    let refined = refine_box(args, bounds, &functions, mode, quiet)?;
    let mesh = refined.mesh()?;
    job.grid = Grid::Mesh(mesh);
    Ok(refined)
}

/// The certified adaptive grid over a box.
pub fn refine_box(
    args: &AdaptiveArgs,
    bounds: [[f64; 3]; 2],
    functions: &[septa::scene::Primitive],
    mode: Mode,
    quiet: bool,
) -> Result<Refined, String> {
    let t0 = Instant::now();
    let mut opts = AdaptiveOptions::for_box(bounds);
    if let Some(d) = args.tolerance {
        opts.tolerance = d;
    }
    if let Some(n) = args.max_tets {
        opts.max_tets = n;
    }
    if let Some(h) = args.min_edge {
        opts.min_edge = h;
    }
    if let Some(n) = args.start_cubes {
        opts.start = n;
    }
    let bar = (!quiet && std::io::IsTerminal::is_terminal(&std::io::stderr())).then(|| {
        let b = indicatif::ProgressBar::new_spinner();
        if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
            b.set_style(style);
        }
        b
    });
    let progress = {
        let bar = bar.clone();
        move |round: usize, leaves: usize| {
            if let Some(b) = &bar {
                b.set_message(format!("adaptive grid: round {round}, {leaves} tets"));
                b.tick();
            }
        }
    };
    let grid =
        refine_with_progress(functions, mode, bounds, &opts, &progress).map_err(|e| format!("--adaptive: {e}"))?;
    if let Some(b) = &bar {
        b.finish_and_clear();
    }
    Ok(Refined { grid, seconds: t0.elapsed().as_secs_f64() })
}

impl Refined {
    /// The grid as a tet mesh for the extraction.
    pub fn mesh(&self) -> Result<septa::grid::TetMesh, String> {
        self.grid.tet_mesh().map_err(|e| format!("--adaptive: internal: the refined grid is not a valid tet mesh: {e}"))
    }
}
