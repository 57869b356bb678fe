//! The `septa` command line: one file per subcommand.
use clap::{Parser, Subcommand};

mod adaptive;
mod args;
mod bench;
mod bench_ceiling;
mod bench_grid;
mod bench_stream;
mod cut;
mod demo;
mod label_names;
mod labels;
mod memcap;
mod network;
mod output;
mod progress;
mod regions;
mod remesh;
mod stress;
mod summary;
mod view;

/// Septa: exact surface networks, non-manifold implicit shapes and planar cut-cell meshes.
#[derive(Parser)]
#[command(name = "septa", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Flush every written file to the disk before it is renamed into place
    /// (survives a crash of the machine, not only of the run; 1-3 ms per
    /// file). Also `SEPTA_FSYNC=1`.
    #[arg(long, global = true)]
    fsync: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Robustness test: random nearly degenerate tetrahedra, each checked for a valid exact result.
    Stress(stress::Args),
    /// Benchmarks.
    Bench(bench::Args),
    /// Implicit arrangement of functions on a tet grid.
    Ia(network::Args),
    /// Material interface of functions on a tet grid.
    Mi(network::Args),
    /// Non-manifold implicit shapes from a scene with a region rule.
    Regions(regions::Args),
    /// Surfaces between the labels of a segmented volume (.npy).
    Labels(labels::Args),
    /// Cut a closed triangle mesh by planes into cut-cells.
    Cut(cut::Args),
    /// Run the built-in scenes.
    Demo(demo::Args),
    /// Write a self-contained viewer for an output folder.
    View(view::Args),
    /// Remesh a written result (its folder's network.npz) to edge length L, in place.
    Remesh(remesh::Args),
}

/// The system allocator, stopping cleanly (exit 2, the limit named) when
/// memory runs out or `SEPTA_MEMORY_LIMIT` is reached (memcap.rs).
#[global_allocator]
static ALLOC: memcap::Capped = memcap::Capped;

fn main() {
    memcap::apply();
    // `septa ... --json | head`: a closed pipe ends the process quietly, as
    // for any Unix filter, instead of a panic in println!.
    #[cfg(unix)]
    // SAFETY: restoring the default action of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // A file size limit (`ulimit -f`) makes a write fail with "File too
    // large" (EFBIG), reported with the file's name and cleaned up like any
    // write error, instead of SIGXFSZ killing the run silently and leaving
    // a staged file.
    #[cfg(unix)]
    // SAFETY: ignoring a signal before any thread starts.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
    // Arrays of 1 MiB and more get pages of their own, given back when
    // freed. glibc's default threshold rises to the largest array freed so
    // far, after which a stage's freed arrays stay resident in the heap next
    // to the next stage's: the peak resident memory of a grid run was 7 MB
    // (10%) above its live data on 18 spheres at 64^3 (docs/performance.md).
    // The smaller arrays stay in the heap, which is not trimmed at every
    // free (a block's outputs, freed once merged, would be faulted in again
    // by the next block's): the grid pipeline gives the heap's free pages
    // back once, after its blocks are merged (`septa::heap`).
    // `septa labels` makes the opposite trade for speed (labels.rs).
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: malloc tuning calls before any thread starts.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 64 << 20);
    }
    // Ctrl-C: remove the partial files of writes in progress and say so; the
    // output folder keeps no manifest.json, so readers see it as incomplete.
    let _ = ctrlc::set_handler(|| {
        INTERRUPTED.store(true, std::sync::atomic::Ordering::SeqCst);
        let n = septa::io::remove_pending_temps();
        eprintln!(
            "\ninterrupted: stopped{}; the output folder is incomplete (no manifest.json) until the job is run again",
            if n > 0 { format!(" and removed {n} partial file(s)") } else { String::new() }
        );
        std::process::exit(130);
    });
    let cli = Cli::parse();
    if cli.fsync {
        septa::io::set_durable(true);
    }
    let result = match cli.command {
        Command::Stress(a) => stress::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Ia(a) => network::run(a, network::Mode::Ia),
        Command::Mi(a) => network::run(a, network::Mode::Mi),
        Command::Regions(a) => regions::run(a),
        Command::Labels(a) => labels::run(a),
        Command::Cut(a) => cut::run(a),
        Command::Demo(a) => demo::run(a),
        Command::View(a) => view::run(a),
        Command::Remesh(a) => remesh::run(a),
    };
    if let Err(e) = result {
        // A write that failed because Ctrl-C removed its partial file is
        // the interrupt's doing: the handler reports it and exits with 130.
        while INTERRUPTED.load(std::sync::atomic::Ordering::SeqCst) {
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

/// Set by the Ctrl-C handler before it removes partial files.
static INTERRUPTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Every subcommand returns this; the message is printed as `error: ...`.
pub type CliResult = Result<(), Box<dyn std::error::Error>>;
