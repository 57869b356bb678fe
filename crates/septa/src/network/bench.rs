//! Entry points for benchmarks (`septa bench grid`): sample primitives on a
//! box grid and compute the network, timing each stage.

use std::time::Instant;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{compute, Mode, Network, NetworkError, NetworkOptions};
use crate::grid::{BoxGrid, Grid, Split};
use crate::io::functions::{sample_grid, Primitive};

/// A timed run on a box grid.
#[derive(Debug)]
pub struct GridRun {
    /// The network (its `seconds` hold the per-stage times).
    pub network: Network,
    /// Seconds to build the grid and sample the functions.
    pub sample_seconds: f64,
    /// Seconds for everything.
    pub total_seconds: f64,
}

/// Samples `functions` on the 5-split box `bounds` of `resolution^3` cubes
/// and computes the network on the current rayon pool.
pub fn run_on_box(
    functions: &[Primitive],
    resolution: usize,
    bounds: [[f64; 3]; 2],
    options: &NetworkOptions,
) -> Result<GridRun, NetworkError> {
    let t0 = Instant::now();
    let g =
        BoxGrid::new([resolution; 3], bounds, Split::Five).map_err(|message| NetworkError::Tet { tet: 0, message })?;
    let grid = Grid::Box(g);
    let values = sample_grid(functions, &grid);
    let sample_seconds = t0.elapsed().as_secs_f64();
    let network = compute(&grid, &values, functions.len(), options)?;
    Ok(GridRun { network, sample_seconds, total_seconds: t0.elapsed().as_secs_f64() })
}

/// Spheres `r - |x - c|` in the pattern of the paper's Sec. 8.3 (IA: unit
/// spheres at the origin, on the axes and at the corners of a cube, jittered
/// by 1e-3; MI: small random spheres, an Apollonius diagram), `k` of them,
/// reproducible from `seed`. For the exact inputs of the reference figures
/// read `spec_json` from the test data instead.
pub fn paper_spheres(mode: Mode, k: usize, seed: u64) -> Vec<Primitive> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(k);
    match mode {
        Mode::Ia => {
            let mut centres: Vec<[f64; 3]> = vec![[0.0; 3], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]];
            for &x in &[-0.4, 0.4] {
                for &y in &[-0.4, 0.4] {
                    for &z in &[-0.4, 0.4] {
                        centres.push([x, y, z]);
                    }
                }
            }
            for a in 0..3 {
                for &s in &[-0.4, 0.4] {
                    let mut c = [0.0; 3];
                    c[a] = s;
                    centres.push(c);
                }
            }
            for i in 0..k {
                let c = centres[i % centres.len()];
                let mut j = || rng.gen_range(-1e-3..1e-3);
                out.push(Primitive::Sphere { center: [c[0] + j(), c[1] + j(), c[2] + j()], radius: 0.5 + j() });
            }
        }
        Mode::Mi => {
            for _ in 0..k {
                let mut c = || rng.gen_range(-0.8..0.8);
                let center = [c(), c(), c()];
                out.push(Primitive::Sphere { center, radius: rng.gen_range(0.01..0.1) });
            }
        }
    }
    out
}
