//! `septa bench`: timings that print ratios against baselines measured in
//! the same run.
use crate::CliResult;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::complex::{Complex, Mode, Options};
use std::time::Instant;

/// Arguments of `septa bench`.
#[derive(clap::Args)]
pub struct Args {
    /// What to time: `tet` (the network inside one tetrahedron, per
    /// tetrahedron), `grid` (a whole grid against marching tetrahedra and a
    /// label-separating extractor) or `stream` (topology from block
    /// summaries while streaming, against the in-memory run).
    what: String,
    /// Grid: cubes per axis.
    #[arg(long, default_value_t = 64, value_parser = crate::args::grid)]
    resolution: usize,
    /// Grid: threads for Septa (the baselines are single-threaded).
    #[arg(long, default_value_t = 1, value_parser = crate::args::threads)]
    threads: usize,
    /// `ia` or `mi`.
    #[arg(long, default_value = "ia")]
    mode: String,
    /// Number of functions per tetrahedron.
    #[arg(long, default_value_t = 1)]
    functions: usize,
    /// Number of tetrahedra.
    #[arg(long, default_value_t = 100_000)]
    count: usize,
    /// Seed of the random functions.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Print one JSON object.
    #[arg(long)]
    json: bool,
    /// Always build each tetrahedron's network step by step (no look-up tables).
    #[arg(long)]
    no_lookup: bool,
    /// Grid: runs of each contender, interleaved; the medians are reported
    /// (a shared machine's load then touches all contenders alike).
    #[arg(long, default_value_t = 3)]
    repeat: usize,
}

/// Runs `septa bench`.
pub fn run(a: Args) -> CliResult {
    match a.what.as_str() {
        "tet" => bench_tet(&a),
        "grid" => crate::bench_grid::bench_grid(&a.mode, a.functions, a.resolution, a.threads, a.repeat, a.json),
        "stream" => crate::bench_stream::bench_stream(&a.mode, a.functions, a.resolution, a.threads, a.repeat, a.json),
        w => Err(format!("unknown benchmark {w:?}; expected `tet`, `grid` or `stream`").into()),
    }
}

/// Random linear functions on a tet, each active: IA functions change sign
/// at the corners (the paper's random planes through the tet); MI values
/// are uniform in [-1, 1].
fn random_tet(rng: &mut ChaCha8Rng, mode: Mode, k: usize) -> Vec<[f64; 4]> {
    (0..k)
        .map(|_| loop {
            let v = [0; 4].map(|_| rng.gen_range(-1.0..1.0));
            let active = v.iter().any(|&x| x > 0.0) && v.iter().any(|&x| x < 0.0);
            if mode == Mode::Mi || active {
                break v;
            }
        })
        .collect()
}

fn bench_tet(a: &Args) -> CliResult {
    let mode = match a.mode.as_str() {
        "ia" => Mode::Ia,
        "mi" => Mode::Mi,
        m => return Err(format!("--mode must be ia or mi, not {m:?}").into()),
    };
    if a.functions == 0 || a.count == 0 {
        return Err("--functions and --count must be positive".into());
    }
    let mut rng = ChaCha8Rng::seed_from_u64(a.seed);
    let inputs: Vec<Vec<[f64; 4]>> = (0..a.count).map(|_| random_tet(&mut rng, mode, a.functions)).collect();
    let mut c = Complex::new();
    let opts = Options::with_lookup(!a.no_lookup);
    let float = Options::with_float(true);
    // Warm up buffers and caches.
    for v in inputs.iter().take(1000) {
        c.build(mode, v, &opts)?;
    }
    let stats_before = septa_exact_stats();
    let mut times = Vec::with_capacity(a.count);
    for v in &inputs {
        let t = Instant::now();
        c.build(mode, v, &opts)?;
        times.push(t.elapsed().as_secs_f64() * 1e6);
    }
    let stats_after = septa_exact_stats();
    let t = Instant::now();
    let mut float_failures = 0;
    for v in &inputs {
        float_failures += c.build(mode, v, &float).is_err() as usize;
    }
    let float_mean = t.elapsed().as_secs_f64() * 1e6 / a.count as f64;
    let n = times.len() as f64;
    let mean = times.iter().sum::<f64>() / n;
    let std = (times.iter().map(|t| (t - mean) * (t - mean)).sum::<f64>() / n).sqrt();
    let hit_rate = filter_hit_rate(stats_before, stats_after);
    // The median resists preemption by other processes, which the mean does not.
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    if a.json {
        println!(
            "{}",
            serde_json::json!({"mode": a.mode, "functions": a.functions, "count": a.count, "lookup": !a.no_lookup, "mean_us": mean,
                "std_us": std, "median_us": median, "filter_hit_rate": hit_rate, "float_mean_us": float_mean,
                "float_failures": float_failures, "exact_over_float": mean / float_mean})
        );
    } else {
        println!(
            "{} k={}: {:.3} us/tet (std {:.3}, median {:.3}) over {} tets; float predicate {:.3} us/tet (exact/float {:.2}x); filter decided {:.4}%",
            a.mode,
            a.functions,
            mean,
            std,
            median,
            a.count,
            float_mean,
            mean / float_mean,
            100.0 * hit_rate
        );
    }
    Ok(())
}

fn septa_exact_stats() -> septa_exact::stats::Stats {
    septa_exact::stats::snapshot()
}

/// Share of exact predicate calls that the floating-point filter decided.
fn filter_hit_rate(before: septa_exact::stats::Stats, after: septa_exact::stats::Stats) -> f64 {
    after.since(&before).filter_rate()
}
