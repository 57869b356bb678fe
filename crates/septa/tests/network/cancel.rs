//! Cancellation is a result, never a panic.

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, NetworkError, NetworkOptions};

#[test]
fn a_cancelled_run_returns_cancelled() {
    let grid = Grid::Box(BoxGrid::new([8; 3], [[-1.0; 3], [1.0; 3]], Split::Five).unwrap());
    let values: Vec<f64> =
        grid.vertices().iter().map(|p| 0.5 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).collect();
    let mut opts = NetworkOptions::new(Mode::Ia);
    opts.block = 4;
    opts.cancel = Some(Arc::new(AtomicBool::new(true)));
    assert!(matches!(compute(&grid, &values, 1, &opts), Err(NetworkError::Cancelled)));
    opts.cancel = Some(Arc::new(AtomicBool::new(false)));
    assert_eq!(compute(&grid, &values, 1, &opts).unwrap().cells.len(), 2);
}
