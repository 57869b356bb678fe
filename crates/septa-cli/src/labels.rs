//! `septa labels`: exact surfaces between the labels of a segmented volume.
use std::path::PathBuf;

use crate::CliResult;
use septa::io::npz::{parse_npy, Array};
use septa::io::regions_out;
use septa::regions::label_surfaces;

/// Arguments of `septa labels`.
#[derive(clap::Args)]
pub struct Args {
    /// A `.npy` array of labels with 3 axes (integer, bool, or float holding
    /// whole numbers; C or Fortran order; either byte order).
    volume: PathBuf,
    #[command(flatten)]
    out: crate::output::Output,
    /// Gaussian smoothing of each label's indicator, in voxels (0: none).
    #[arg(long, default_value_t = 0.0, value_parser = crate::args::sigma)]
    sigma: f64,
}

/// Runs `septa labels`.
pub fn run(a: Args) -> CliResult {
    let file = a.volume.display().to_string();
    let bytes = std::fs::read(&a.volume).map_err(|e| format!("{file}: cannot read: {e}"))?;
    let (shape, labels) = match parse_npy(&bytes).map_err(|e| format!("{file}: {e}"))? {
        Array::I64(shape, _) | Array::F64(shape, _) if shape.len() != 3 => {
            return Err(format!("{file}: labels must have 3 axes, not shape {shape:?}").into())
        }
        Array::I64(shape, data) => ([shape[0], shape[1], shape[2]], data),
        // Float label volumes (as some tools save them): whole numbers only.
        Array::F64(shape, data) => {
            let mut out = Vec::with_capacity(data.len());
            for (i, x) in data.into_iter().enumerate() {
                if !(x.is_finite() && x.fract() == 0.0 && x.abs() < 9.0e15) {
                    let at = [i / (shape[1] * shape[2]), (i / shape[2]) % shape[1], i % shape[2]];
                    return Err(format!("{file}: voxel {at:?} has label {x}, not a whole number").into());
                }
                out.push(x as i64);
            }
            ([shape[0], shape[1], shape[2]], out)
        }
        Array::Str(_) => return Err(format!("{file}: labels must be a numeric array, not a string").into()),
    };
    let quiet = a.out.json || a.out.quiet;
    let r =
        crate::progress::during(quiet, "label surfaces", || a.out.install(|| label_surfaces(&labels, shape, a.sigma)))?
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
