//! `septa labels`: exact surfaces between the labels of a segmented volume.
use std::path::PathBuf;

use crate::CliResult;
use septa::io::npz::{parse_npy, Array};
use septa::io::regions_out;
use septa::regions::label_surfaces;

/// Arguments of `septa labels`.
#[derive(clap::Args)]
pub struct Args {
    /// A `.npy` array of integer labels with 3 axes (C order).
    volume: PathBuf,
    #[command(flatten)]
    out: crate::output::Output,
    /// Gaussian smoothing of each label's indicator, in voxels (0: none).
    #[arg(long, default_value_t = 0.0)]
    sigma: f64,
}

/// Runs `septa labels`.
pub fn run(a: Args) -> CliResult {
    let file = a.volume.display().to_string();
    let bytes = std::fs::read(&a.volume).map_err(|e| format!("{file}: cannot read: {e}"))?;
    let (shape, labels) = match parse_npy(&bytes).map_err(|e| format!("{file}: {e}"))? {
        Array::I64(shape, data) if shape.len() == 3 => ([shape[0], shape[1], shape[2]], data),
        Array::I64(shape, _) => return Err(format!("{file}: labels must have 3 axes, not shape {shape:?}").into()),
        _ => return Err(format!("{file}: labels must be an integer array").into()),
    };
    let quiet = a.out.json || a.out.quiet;
    let r = crate::progress::during(quiet, "label surfaces", || a.out.install(|| label_surfaces(&labels, shape, a.sigma)))?
        .map_err(|e| format!("{file}: {e}"))?;
    crate::progress::during(quiet, &format!("writing {}", a.out.output.display()), || {
        regions_out::write_formats(&r, &a.out.output, &a.out.format.0)
    })?;
    let summary = regions_out::summary(&r);
    if a.out.json {
        println!("{summary}");
    } else if a.out.talk() {
        println!("{file}: {} surfaces, {} curves, {} polygons", r.surfaces.len(), r.curves.len(), r.faces.len());
    }
    Ok(())
}
