//! `septa bench stream`: the streamed network with its topology assembled
//! from block summaries (docs/sparse.md) against the in-memory sparse run on the
//! same input, in one run, and against streaming the polygons alone (what
//! the summaries and their assembly cost).
//!
//! Functions: the reference cases' spheres (`data/specs/`, first `K` of 18),
//! on a `R^3` box grid over `[-1, 1]^3`, 5 tets per cube, sparse. Streamed
//! blocks go to a sink that only counts (no file: the PLY writer's time is
//! `septa ia --stream`'s `ply` stage). Each contender runs `--repeat` times,
//! interleaved; medians are compared. The streamed counts must equal the
//! in-memory ones, or the benchmark fails. Peak memory cannot be told apart
//! inside one process: measure it per command (docs/sparse.md).
use crate::CliResult;
use septa::complex::Mode;
use septa::grid::{BoxGrid, Split};
use septa::network::compute_sparse;
use septa::network::NetworkOptions;
use septa::network::{stream_sparse, stream_topology, StreamBlock, StreamSink};
use septa::scene::load_function_list;
use std::time::Instant;

const IA_SPHERES: &str = include_str!("../../../data/specs/ia18.json");
const MI_SPHERES: &str = include_str!("../../../data/specs/mi18.json");

/// Counts polygons (the cheapest sink: what is timed is the stream itself).
struct Count(usize);

impl StreamSink for Count {
    fn block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        self.0 += b.num_polygons();
        Ok(())
    }
}

/// Runs the streaming benchmark and prints times and ratios.
pub fn bench_stream(mode: &str, k: usize, res: usize, threads: usize, repeat: usize, json: bool) -> CliResult {
    let (mode, spec) = match mode {
        "ia" => (Mode::Ia, IA_SPHERES),
        "mi" => (Mode::Mi, MI_SPHERES),
        m => return Err(format!("--mode must be ia or mi, not {m:?}").into()),
    };
    let functions = load_function_list(spec, "data/specs", None)?;
    if k == 0 || k > functions.len() {
        return Err(format!("--functions must be 1..={}", functions.len()).into());
    }
    let f = &functions[..k];
    let grid = BoxGrid::new([res; 3], [[-1.0; 3], [1.0; 3]], Split::Five)?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads.max(1)).build()?;
    let o = NetworkOptions::new(mode);
    let (mut tm, mut tt, mut tp) = (vec![], vec![], vec![]);
    let mut last = None;
    for _ in 0..repeat.max(1) {
        let t = Instant::now();
        let (net, _) = pool.install(|| compute_sparse(&grid, f, &o))?;
        tm.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let (_, sum) = pool.install(|| stream_topology(&grid, f, &o, 0, &mut Count(0)))?;
        tt.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        pool.install(|| stream_sparse(&grid, f, &o, 0, &mut Count(0)))?;
        tp.push(t.elapsed().as_secs_f64());
        if sum.counts() != net.counts() {
            return Err(format!(
                "streamed topology differs from the in-memory network: {:?} vs {:?}",
                sum.counts(),
                net.counts()
            )
            .into());
        }
        last = Some(net);
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (t_mem, t_topo, t_poly) = (median(tm), median(tt), median(tp));
    let net = last.expect("at least one run");
    let name = if mode == Mode::Ia { "ia" } else { "mi" };
    if json {
        println!(
            "{}",
            serde_json::json!({
                "mode": name, "functions": k, "resolution": res, "threads": threads, "repeat": repeat.max(1),
                "active_tets": net.active_tets,
                "seconds": {"in_memory": t_mem, "stream_topology": t_topo, "stream_polygons": t_poly},
                "ratios": {"stream_topology_over_in_memory": t_topo / t_mem,
                    "stream_topology_over_stream_polygons": t_topo / t_poly},
                "counts": net.counts().into_iter().collect::<std::collections::BTreeMap<_, _>>(),
            })
        );
    } else {
        println!(
            "{} {k} functions, {res}^3 cubes ({} active tets), {threads} thread(s), median of {} interleaved runs",
            name.to_uppercase(),
            net.active_tets,
            repeat.max(1)
        );
        println!("  in memory (sparse, with topology)   {t_mem:8.3} s");
        println!("  streamed with topology              {t_topo:8.3} s   = {:.2}x in memory", t_topo / t_mem);
        println!(
            "  streamed polygons only              {t_poly:8.3} s   (topology from summaries adds {:.0}%)",
            100.0 * (t_topo / t_poly - 1.0)
        );
        println!("  counts (equal): {:?}", net.counts());
    }
    Ok(())
}
