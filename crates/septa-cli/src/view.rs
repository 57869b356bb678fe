//! `septa view OUTDIR`: writes a self-contained viewer folder for a job's
//! output and opens it. The page and its data are written by the library
//! (`septa::io::write_result_viewer`, the writer Python's `septa.view` uses).
use crate::CliResult;
use std::path::{Path, PathBuf};

/// Arguments of `septa view`.
#[derive(clap::Args)]
pub struct Args {
    /// Output folder of `septa ia|mi|regions|labels|cut` (holding
    /// network.json, or cells.obj and cut.json for a cut), or a stream's
    /// folder or file (`--stream OUT.ply` or `OUT.vtu`, with
    /// OUT.topology.json beside it).
    pub outdir: PathBuf,
    /// Only write the viewer and print its path; do not start a browser.
    #[arg(long)]
    pub no_open: bool,
    /// Title shown in the viewer (default: the folder name).
    #[arg(long)]
    pub title: Option<String>,
}

/// Runs `septa view`.
pub fn run(args: Args) -> CliResult {
    let title = args.title.clone().unwrap_or_else(|| folder_name(&args.outdir));
    let index = write_viewer(&args.outdir, &title)?;
    println!("viewer: {}", index.display());
    if !args.no_open && has_display() {
        if let Err(e) = open_in_browser(&index) {
            eprintln!("could not start a browser ({e}); open the file above by hand");
        }
    } else if !args.no_open {
        println!("no display found: open the file above in a browser");
    }
    Ok(())
}

/// The result folder's name (a stream file's folder for a file).
fn folder_name(dir: &Path) -> String {
    std::fs::canonicalize(dir)
        .ok()
        .map(|p| if p.is_file() { p.parent().map(Path::to_path_buf).unwrap_or(p) } else { p })
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
        .unwrap_or_else(|| "Septa".to_string())
}

/// Writes `OUTDIR/viewer/{index.html, viewer.js, data.js}` (the library's
/// one viewer writer) and returns the path of `index.html`. Used by `septa
/// view` and `septa demo`.
pub fn write_viewer(outdir: &Path, title: &str) -> Result<PathBuf, Box<dyn std::error::Error>> {
    Ok(septa::io::write_result_viewer(outdir, title, None)?)
}

fn has_display() -> bool {
    cfg!(target_os = "macos")
        || cfg!(windows)
        || std::env::var_os("DISPLAY").is_some()
        || std::env::var_os("WAYLAND_DISPLAY").is_some()
}

fn open_in_browser(index: &Path) -> std::io::Result<()> {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(windows) {
        "explorer"
    } else {
        "xdg-open"
    };
    std::process::Command::new(opener)
        .arg(index)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .map(|_| ())
}
