//! A differential harness on generated scenes with round numbers: planes
//! through grid vertices along axis and diagonal directions, spheres centred
//! at grid vertices with radii that are whole multiples of the grid step (so
//! they pass through grid vertices), exact duplicates, normals scaled by 2,
//! in IA and MI. Each scene runs dense (1 thread) and sparse (1 and 2
//! threads) with byte-identical networks, and streamed with topology equal
//! to the in-memory network face by face; cells by ray shooting equal cells
//! by grouping every tet. Every scene must run sparsely without falling
//! back, with cells by ray shooting, no crack (an edge of one face off the
//! grid boundary) and a stream that accepts it. Seeded;
//! `SEPTA_ROUND_SCENES=N` runs N scenes instead of the default few.

use crate::common;

use septa::complex::Mode;
use septa::job::{GridOverride, Job};
use septa::network::NetworkOptions;
use septa::scene::load_function_list;

use common::{assert_same_network, cube_grid};

/// SplitMix64: a small seeded generator (the scenes must be the same on every machine).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// A scene: a function list (JSON), its grid resolution on [-1, 1]^3 and a mode.
fn scene(rng: &mut Rng) -> (String, usize, Mode) {
    let n = [6, 8, 10, 12][rng.below(4)];
    let h = 2.0 / n as f64;
    let node = |rng: &mut Rng| [0; 3].map(|_| -1.0 + h * rng.below(n + 1) as f64);
    let dirs: [[f64; 3]; 8] = [
        [1., 0., 0.],
        [0., 1., 0.],
        [0., 0., 1.],
        [1., 1., 0.],
        [1., -1., 0.],
        [0., 1., 1.],
        [1., 1., 1.],
        [2., 1., 0.],
    ];
    let mut fs: Vec<String> = Vec::new();
    for _ in 0..2 + rng.below(3) {
        let f = match rng.below(5) {
            0 | 1 => {
                let d = dirs[rng.below(dirs.len())];
                let s = if rng.below(2) == 0 { 1.0 } else { -2.0 };
                let p = node(rng);
                format!(
                    r#"{{"type": "plane", "point": [{}, {}, {}], "normal": [{}, {}, {}]}}"#,
                    p[0],
                    p[1],
                    p[2],
                    s * d[0],
                    s * d[1],
                    s * d[2]
                )
            }
            2 | 3 => {
                let c = node(rng);
                let r = h * (1 + rng.below(n / 2)) as f64;
                format!(r#"{{"type": "sphere", "center": [{}, {}, {}], "radius": {r}}}"#, c[0], c[1], c[2])
            }
            _ if !fs.is_empty() => fs[rng.below(fs.len())].clone(),
            _ => r#"{"type": "sphere", "center": [0, 0, 0], "radius": 0.5}"#.to_string(),
        };
        fs.push(f);
    }
    let mode = if rng.below(2) == 0 { Mode::Ia } else { Mode::Mi };
    (format!("[{}]", fs.join(",\n ")), n, mode)
}

#[test]
fn generated_round_scenes_give_one_answer_on_every_path() {
    let count: usize = std::env::var("SEPTA_ROUND_SCENES").ok().and_then(|s| s.parse().ok()).unwrap_or(40);
    let mut rng = Rng(20261201);
    let dir = std::env::temp_dir().join(format!("septa-round-scenes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (mut streamed, mut refused) = (0, 0);
    for i in 0..count {
        let (text, n, mode) = scene(&mut rng);
        let what = format!("scene-{i}");
        eprintln!("{what} ({mode:?}, {n}^3): {text}");
        let path = dir.join(format!("scene{i}.json"));
        std::fs::write(&path, &text).unwrap();
        let over = GridOverride { resolution: Some(n), ..Default::default() };
        let job = Job::load(path.to_str().unwrap(), &over).unwrap();
        let mut o = NetworkOptions::new(mode);
        o.block = 4;
        let pool = |t: usize| rayon::ThreadPoolBuilder::new().num_threads(t).build().unwrap();
        let (dense, _) = pool(1).install(|| job.run(&o, true)).unwrap_or_else(|e| panic!("{what}: {e}"));
        // Cells by ray shooting (with shells linked where sheets touch at
        // points) equal cells by grouping every tet, an independent method.
        let mut og = o.clone();
        og.raytrace = false;
        let (grouped, _) = pool(1).install(|| job.run(&og, true)).unwrap();
        assert_eq!(grouped.cells_method, "grouping", "{what}");
        // How shells group into cells is the same. Two differences of form
        // remain where faces lie on the grid boundary (a plane through the
        // boundary's grid vertices): grouping gives no cell to the outer side
        // of such a face, ray shooting a cell of its own; and grouping can
        // list cells bounded by no shell there. Both are compared apart.
        let (ray, group) = (common::cell_partition(&dense), common::cell_partition(&grouped));
        let grouped_shells: std::collections::HashSet<u32> = group.iter().flat_map(|c| c.0.iter().copied()).collect();
        let (inside, outside): (Vec<_>, Vec<_>) =
            ray.into_iter().partition(|c| c.0.iter().any(|s| grouped_shells.contains(s)));
        let with_shells: Vec<_> = group.iter().filter(|c| !c.0.is_empty()).cloned().collect();
        assert_eq!(inside, with_shells, "{what}: ray vs grouping");
        assert!(outside.iter().all(|c| c.0.len() <= 1), "{what}: cells without grouping's shells: {outside:?}");
        // No crack: every edge off the grid boundary bounds two or more faces
        // (one point never reached under two keys).
        assert!(!common::cracked(&dense, &cube_grid(n)), "{what}: an edge of one face off the grid boundary");
        for threads in [1, 2] {
            let (sparse, stats) = pool(threads).install(|| job.run(&o, false)).unwrap();
            assert_same_network(&dense, &sparse, &format!("{what}: sparse, {threads} threads"));
            // The sparse path itself, cells by ray shooting: no fallback.
            assert!(!stats.is_some_and(|s| s.dense_fallback), "{what}: dense fallback");
            assert_eq!(sparse.cells_method, "raytrace", "{what}");
        }
        let f = load_function_list(&text, "scene", None).unwrap();
        match super::stream_topology::check(&cube_grid(n), &f, mode, 4, 1 + i % 3, &what) {
            Some(_) => streamed += 1,
            None => refused += 1,
        }
    }
    eprintln!("{count} generated scenes: {streamed} streamed face by face, {refused} refused (grouped in memory)");
    assert_eq!(refused, 0, "every generated scene streams with topology");
    let _ = std::fs::remove_dir_all(&dir);
}
