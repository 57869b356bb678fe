//! `septa labels`: exact surfaces between the labels of a segmented volume.
use std::path::PathBuf;

use crate::CliResult;
use septa::io::{diagonal_affine, read_label_volume};
use septa::io::{regions_summary, write_regions_formats};
use septa::regions::label_surfaces_with_progress;

/// Arguments of `septa labels`.
#[derive(clap::Args)]
pub struct Args {
    /// A label volume with 3 axes: `.npy` (integer, bool, or float holding
    /// whole numbers; C or Fortran order; either byte order), NIfTI-1
    /// (`.nii`, `.nii.gz`) or NRRD (`.nrrd`, data attached). NIfTI and NRRD
    /// files are placed by their voxel-to-world map as nibabel and pynrrd
    /// read it (rotations, shears and flips included).
    volume: PathBuf,
    #[command(flatten)]
    out: crate::output::Output,
    /// Gaussian smoothing of each label's indicator, in voxels (0: none).
    #[arg(long, default_value_t = 0.0, value_parser = crate::args::sigma)]
    sigma: f64,
    /// Voxel size per axis: points are `origin + index * spacing` (replaces
    /// the file's own map).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], value_parser = crate::args::positive)]
    spacing: Option<Vec<f64>>,
    /// World position of voxel (0, 0, 0) (replaces the file's own map).
    #[arg(long, num_args = 3, value_names = ["X", "Y", "Z"], value_parser = crate::args::finite, allow_hyphen_values = true)]
    origin: Option<Vec<f64>>,
    /// Label names: a JSON object `{"1": "liver", "2": "kidney"}` (label ->
    /// name), written to network.json's `names` (the viewer shows them) and
    /// printed in the summary.
    #[arg(long, value_name = "FILE.json")]
    names: Option<PathBuf>,
}

/// Runs `septa labels`.
pub fn run(a: Args) -> CliResult {
    keep_freed_memory();
    let file = a.volume.display().to_string();
    // the small file first: a bad table fails before the work
    let names = a.names.as_deref().map(crate::label_names::read_label_names).transpose()?;
    let vol = read_label_volume(&a.volume)?;
    let affine = if a.spacing.is_some() || a.origin.is_some() {
        let s = a.spacing.as_deref().unwrap_or(&[1.0; 3]);
        let o = a.origin.as_deref().unwrap_or(&[0.0; 3]);
        diagonal_affine([s[0], s[1], s[2]], [o[0], o[1], o[2]])
    } else {
        vol.affine
    };
    // before the work: a map that takes the volume outside the doubles
    septa::io::check_placement(&affine, vol.shape).map_err(|e| {
        if a.spacing.is_some() || a.origin.is_some() {
            format!("--spacing/--origin: {e}")
        } else {
            format!("{file}: {e}")
        }
    })?;
    let quiet = a.out.json || a.out.quiet;
    // A counted bar over the network's blocks, then a spinner naming the
    // stage after them (the surfaces of the label pairs).
    let (bar, progress) = crate::progress::block_bar(quiet, "label surfaces: pairs, curves");
    let r = a.out.install(|| label_surfaces_with_progress(&vol.labels, vol.shape, a.sigma, progress));
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let mut r = r?.map_err(|e| format!("{file}: {e}"))?;
    if let Some(names) = names {
        r.names.regions = names;
    }
    a.out
        .install(|| septa::mesh::place_labels(&mut r, vol.shape, &affine, !a.out.no_certify))?
        .map_err(|e| format!("{file}: {e}"))?;
    let remeshed = match a.out.remesh {
        Some(l) => {
            let bounds = septa::mesh::label_bounds(vol.shape, &affine);
            let o = septa::mesh::RemeshOptions::new(l);
            Some(
                a.out
                    .install(|| septa::mesh::remesh_regions(&mut r, &o, bounds))?
                    .map_err(|e| format!("{file}: {e}"))?,
            )
        }
        None => None,
    };
    crate::progress::during(quiet, &format!("writing {}", a.out.output.display()), || {
        write_regions_formats(&r, &a.out.output, &a.out.format.0)
    })?;
    let mut summary = regions_summary(&r);
    if let (Some(m), Some(obj)) = (&remeshed, summary.as_object_mut()) {
        obj.insert("remesh".into(), serde_json::to_value(m)?);
    }
    if a.out.json {
        println!("{summary}");
    } else if a.out.talk() {
        print!("{}", crate::summary::regions_text(&file, &r));
        a.out.tell_embedding(r.embedding.as_ref());
        a.out.tell_solids();
        a.out.tell_remesh(remeshed.as_ref());
    }
    Ok(())
}

/// Lets glibc's allocator reuse freed memory instead of handing it back and
/// faulting in fresh zeroed pages for the next array: the stages of a label
/// run each build and drop arrays of megabytes, and page faults of fresh
/// arrays were a fifth of a 128^3 run. Allocations up to 32 MiB come from the
/// heap (not from a fresh mapping each), and the heap is not trimmed while
/// the process runs, nor between the grid pipeline's stages
/// (`septa::heap`). Costs some resident memory (about 15% more on 128^3).
pub(crate) fn keep_freed_memory() {
    septa::heap::set_release_free_memory(false);
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes allocator parameters; no memory is touched.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
    }
}
