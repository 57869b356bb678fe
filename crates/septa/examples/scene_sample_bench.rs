//! Sampling throughput: every built-in scene's functions at its grid scaled
//! to `n^3` cubes, 1 thread against all threads.
//!
//! `cargo run --release -p septa --example scene_sample_bench -- 100`
use septa::scene::{builtin, sample_grid};

fn main() {
    let n: usize = std::env::args().nth(1).map_or(100, |x| x.parse().unwrap());
    for (name, _) in builtin::list() {
        let mut s = builtin::get(name).unwrap();
        s.grid.resolution = [n; 3];
        let pts = s.grid.vertices();
        let mut line = format!("{name:20} {:>9} vertices x {:>2} functions:", pts.len(), s.functions.len());
        for threads in [1, 0] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let t = std::time::Instant::now();
            let v = pool.install(|| sample_grid(&s.functions, &pts));
            let dt = t.elapsed().as_secs_f64();
            line += &format!(
                "  {} thread(s) {:.3} s ({:.0} M values/s)",
                pool.current_num_threads(),
                dt,
                v.len() as f64 / dt / 1e6
            );
        }
        println!("{line}");
    }
}
