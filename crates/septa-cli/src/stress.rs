//! `septa stress`: the robustness test of Du et al. Table 1.
use crate::CliResult;
use septa::complex::stress::{stress, Degeneracy};
use septa::complex::{Mode, Options};

/// Arguments of `septa stress`.
#[derive(clap::Args)]
pub struct Args {
    /// `ia` (4 functions) or `mi` (5 functions).
    #[arg(long, default_value = "ia")]
    mode: String,
    /// `point`, `segment`, `tri`, `quad`, or `all`.
    #[arg(long, default_value = "all")]
    degeneracy: String,
    /// Number of inputs per degeneracy.
    #[arg(long, default_value_t = 10_000)]
    count: usize,
    /// Seed of the input generator.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Use the naive floating-point predicate.
    #[arg(long)]
    float: bool,
    /// Print one JSON object per line.
    #[arg(long)]
    json: bool,
}

/// Runs `septa stress`.
pub fn run(a: Args) -> CliResult {
    let mode = match a.mode.as_str() {
        "ia" => Mode::Ia,
        "mi" => Mode::Mi,
        m => return Err(format!("--mode must be ia or mi, not {m:?}").into()),
    };
    let kinds: Vec<&str> =
        if a.degeneracy == "all" { vec!["point", "segment", "tri", "quad"] } else { vec![a.degeneracy.as_str()] };
    let options = Options::with_float(a.float);
    if !a.json {
        println!("{:<6} {:<8} {:>7} {:>9} {:>9} {:>9}", "mode", "degen", "cases", "success", "type I", "type II");
    }
    for kind in kinds {
        let d =
            Degeneracy::parse(kind).ok_or(format!("--degeneracy must be point|segment|tri|quad|all, not {kind:?}"))?;
        let r = stress(mode, d, a.count, a.seed, &options);
        if a.json {
            println!(
                "{}",
                serde_json::json!({"mode": a.mode, "degeneracy": kind, "float": a.float, "cases": r.cases,
                    "success": r.success, "type1": r.type1, "type2": r.type2})
            );
        } else {
            let pct = |x: usize| 100.0 * x as f64 / r.cases.max(1) as f64;
            println!(
                "{:<6} {:<8} {:>7} {:>8.2}% {:>8.2}% {:>8.2}%",
                a.mode,
                kind,
                r.cases,
                pct(r.success),
                pct(r.type1),
                pct(r.type2)
            );
        }
    }
    Ok(())
}
