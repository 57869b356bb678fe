//! `septa bench grid`: the whole network against baselines on the same
//! input, in one run (Du et al. Sec. 8.3).
//!
//! Functions are the reference cases' spheres (`data/specs/`, first `K` of
//! 18: the paper's regular pattern for IA, an Apollonius diagram for MI),
//! sampled on a `R^3` box grid split into 5 tets per cube. Each contender
//! runs `--repeat` times, interleaved, and the medians are compared.
use crate::CliResult;
use septa::baseline::{label_separating, marching_tets};
use septa::complex::Mode;
use septa::grid::{BoxGrid, Grid, Split};
use septa::network::{compute, NetworkOptions};
use septa::scene::{load_function_list, sample_grid};
use std::time::Instant;

const IA_SPHERES: &str = include_str!("../../../data/specs/ia18.json");
const MI_SPHERES: &str = include_str!("../../../data/specs/mi18.json");

fn secs<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64())
}

/// Runs the grid benchmark and prints times and ratios.
pub fn bench_grid(mode: &str, k: usize, res: usize, threads: usize, repeat: usize, json: bool) -> CliResult {
    let (mode, spec, mi) = match mode {
        "ia" => (Mode::Ia, IA_SPHERES, false),
        "mi" => (Mode::Mi, MI_SPHERES, true),
        m => return Err(format!("--mode must be ia or mi, not {m:?}").into()),
    };
    let functions = load_function_list(spec, "data/specs", None)?;
    if k == 0 || k > functions.len() {
        return Err(format!("--functions must be 1..={}", functions.len()).into());
    }
    let functions = &functions[..k];
    let grid = Grid::Box(BoxGrid::new([res; 3], [[-1.0; 3], [1.0; 3]], Split::Five)?);
    let points = grid.vertices();
    let (values, t_sample) = secs(|| sample_grid(functions, &points));
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.max(1)).build()?;
    let run = |float: bool| {
        let mut o = NetworkOptions::new(mode);
        o.float = float;
        pool.install(|| compute(&grid, &values, k, &o))
    };
    // Interleaved runs; medians. Only the last run's outputs are kept.
    let tets: Vec<[u32; 4]> = (0..grid.num_tets()).map(|t| grid.tet(t)).collect();
    let (mut te, mut tx, mut tf, mut tm, mut tl) = (vec![], vec![], vec![], vec![], vec![]);
    let (mut last_net, mut last_float, mut last_mt, mut last_ls) = (None, None, None, None);
    for _ in 0..repeat.max(1) {
        let (net, t) = secs(|| run(false));
        let net = net?;
        te.push(t);
        tx.push(net.seconds.iter().filter(|(s, _)| *s == "tets" || *s == "merge").map(|(_, t)| t).sum());
        last_net = Some(net);
        let (float_net, t) = secs(|| run(true));
        tf.push(t);
        last_float = Some(float_net);
        let (mt, t) = secs(|| marching_tets(&points, &tets, &values, k));
        tm.push(t);
        last_mt = Some(mt);
        let (ls, t) = secs(|| label_separating(&points, &tets, &values, k, mi));
        tl.push(t);
        last_ls = Some(ls);
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (t_exact, extract, t_float, t_mt, t_ls) = (median(te), median(tx), median(tf), median(tm), median(tl));
    let (net, float_net, mt, ls) = (last_net.unwrap(), last_float.unwrap(), last_mt.unwrap(), last_ls.unwrap());
    // With several threads: Septa on one thread, and the machine's ceiling
    // for the same thread count (busy copies of the single-threaded
    // marching tetrahedra), so the speed-up is read against what the
    // machine gives right now.
    let scaling = if threads > 1 {
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
        let mut t1 = Vec::new();
        for _ in 0..repeat.max(1) {
            let o = NetworkOptions::new(mode);
            t1.push(secs(|| one.install(|| compute(&grid, &values, k, &o))).1);
        }
        let t1 = median(t1);
        let ceiling = crate::bench_ceiling::ceiling(threads, &|| {
            std::hint::black_box(marching_tets(&points, &tets, &values, k));
        });
        Some((t1, t1 / t_exact, ceiling))
    } else {
        None
    };
    let float_note = match &float_net {
        Ok(n) if n.counts() == net.counts() => "same counts".to_string(),
        Ok(_) => "different counts".to_string(),
        Err(e) => format!("failed: {e}"),
    };
    if json {
        println!(
            "{}",
            serde_json::json!({
                "mode": if mi { "mi" } else { "ia" }, "functions": k, "resolution": res, "threads": threads,
                "tets": grid.num_tets(), "active_tets": net.active_tets, "repeat": repeat.max(1),
                "seconds": {"sample": t_sample, "network": t_exact, "extract": extract, "float_network": t_float,
                    "marching_tets": t_mt, "label_separating": t_ls},
                "ratios": {"extract_over_label_separating": extract / t_ls, "network_over_label_separating": t_exact / t_ls,
                    "exact_over_float": t_exact / t_float, "network_over_marching_tets": t_exact / t_mt},
                "float": float_note,
                "counts": net.counts().into_iter().collect::<std::collections::BTreeMap<_, _>>(),
                "baseline_polygons": {"marching_tets": mt.num_polygons(), "label_separating": ls.num_polygons()},
                "scaling": scaling.map(|(t1, speedup, ceiling)| serde_json::json!({
                    "network_one_thread": t1, "speedup": speedup, "machine_ceiling": ceiling})),
            })
        );
    } else {
        let m = if mi { "MI" } else { "IA" };
        println!(
            "{m} {k} functions, {res}^3 cubes ({} tets, {} active), Septa on {threads} thread(s), median of {} interleaved runs",
            grid.num_tets(),
            net.active_tets,
            repeat.max(1)
        );
        println!("  sampling            {t_sample:8.3} s");
        println!("  Septa network       {t_exact:8.3} s   (stages: {:?})", net.seconds);
        println!("  Septa to polygons   {extract:8.3} s   = {:.2}x label-separating", extract / t_ls);
        println!("  float predicates    {t_float:8.3} s   exact/float = {:.2}x ({float_note})", t_exact / t_float);
        println!("  marching tets       {t_mt:8.3} s   ({} polygons)", mt.num_polygons());
        println!("  label-separating    {t_ls:8.3} s   ({} polygons)", ls.num_polygons());
        if let Some((t1, speedup, ceiling)) = scaling {
            println!(
                "  Septa on 1 thread   {t1:8.3} s   {threads}-thread speed-up {speedup:.2}x; machine ceiling now {ceiling:.2}x ({threads} busy copies of marching tets)"
            );
        }
        println!("  counts: {:?}", net.counts());
    }
    Ok(())
}
