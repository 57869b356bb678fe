//! Block statistics of sparse evaluation for a scene: how many blocks the
//! primitives' bounds skip, against how many are truly empty on the grid.
//!
//! `cargo run --release -p septa --example scene_block_stats -- builtin:apollonius-18 200 16`
use septa::scene::{sample_grid, Mode, Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let mut s = Scene::load(args.get(1).map_or("builtin:apollonius-18", |s| s.as_str())).unwrap();
    let res: usize = args.get(2).map_or(100, |x| x.parse().unwrap());
    let b: usize = args.get(3).map_or(16, |x| x.parse().unwrap());
    s.grid.resolution = [res; 3];
    let k = s.functions.len();
    let (mut total, mut skipped, mut empty) = (0, 0, 0);
    let t = std::time::Instant::now();
    for bi in (0..res).step_by(b) {
        for bj in (0..res).step_by(b) {
            for bk in (0..res).step_by(b) {
                total += 1;
                let first = [bi, bj, bk];
                let last = [0, 1, 2].map(|a| (first[a] + b).min(res));
                if !s.block_may_be_active(first, last) {
                    skipped += 1;
                }
                let mut pts = vec![];
                for i in first[0]..=last[0] {
                    for j in first[1]..=last[1] {
                        for l in first[2]..=last[2] {
                            pts.push(s.grid.vertex([i, j, l]));
                        }
                    }
                }
                let v = sample_grid(&s.functions, &pts);
                let label = |r: &[f64]| -> Vec<bool> {
                    match s.mode {
                        // A zero value is on the network: never uniform.
                        Mode::Ia if r.contains(&0.0) => vec![],
                        Mode::Ia => r.iter().map(|x| *x > 0.0).collect(),
                        Mode::Mi => {
                            let m = (0..k).max_by(|&a, &c| r[a].total_cmp(&r[c])).unwrap();
                            (0..k).map(|j| j == m).collect()
                        }
                    }
                };
                let rows: Vec<&[f64]> = v.chunks(k).collect();
                let l0 = label(rows[0]);
                if !l0.is_empty() && rows.iter().all(|r| label(r) == l0) {
                    empty += 1;
                }
            }
        }
    }
    let t2 = std::time::Instant::now();
    let (v, values) = s.sample();
    println!("dense sampling: {} vertices x {k} functions in {:.2} s", v.len(), t2.elapsed().as_secs_f64());
    drop((v, values));
    println!(
        "{} res {res} block {b}: {total} blocks, {skipped} skipped by bounds, {empty} uniform on the grid ({:.2} s)",
        args.get(1).map_or("builtin:apollonius-18", |s| s.as_str()),
        t.elapsed().as_secs_f64()
    );
}
