//! One answer on every path: scenes with round numbers (spheres and planes
//! through grid vertices, duplicated and scaled functions, material ties,
//! tangencies, functions vanishing on whole tet faces), each run dense,
//! sparse, with 1 and 2 threads, streamed with topology, and read from a
//! function list and from a scene file. Every in-memory run must give the
//! same `network.json` bytes, the stream the same counts; analytic counts
//! where the geometry gives them; and each case says which path must run
//! (no silent dense fallback where the sparse path applies).

use crate::common;

use septa::complex::Mode;
use septa::job::{GridOverride, Job};
use septa::network::{stream_topology, Network, NetworkOptions, StreamBlock, StreamSink};

use common::assert_same_network;

/// A case: functions as a reference function list (JSON text), a mode, a
/// grid resolution on `[-1, 1]^3`, what the sparse path must do, and the
/// counts the geometry gives (name, value).
struct Case {
    name: &'static str,
    functions: &'static str,
    mode: Mode,
    n: usize,
    /// The sparse path must not fall back to the dense one.
    sparse_holds: bool,
    /// The stream with topology must accept the input.
    streams: bool,
    counts: &'static [(&'static str, usize)],
}

const ROUND_SPHERES: &str = r#"[
 {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
 {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
 {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5},
 {"type": "sphere", "center": [0, 0, 0.5], "radius": 0.5}]"#;

const PLANES_AND_SPHERE: &str = r#"[
 {"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]},
 {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},
 {"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]},
 {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#;

fn cases() -> Vec<Case> {
    vec![
        // The paper's 4 spheres (Du et al. Sec. 8.3) through grid vertices:
        // the reference's combinatorics.
        Case {
            name: "round spheres IA",
            functions: ROUND_SPHERES,
            mode: Mode::Ia,
            n: 16,
            sparse_holds: true,
            streams: true,
            counts: &[
                ("patches", 32),
                ("chains", 24),
                ("corners", 8),
                ("shells", 16),
                ("cells", 16),
                ("components", 1),
            ],
        },
        // Their bisector planes (x, y, z = 0.25) are grid planes: the
        // interface lies in tet faces, and rays start at grid vertices.
        Case {
            name: "round spheres MI",
            functions: ROUND_SPHERES,
            mode: Mode::Mi,
            n: 16,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 6), ("chains", 4), ("corners", 5), ("cells", 4), ("components", 1)],
        },
        // Octants cut by a sphere: 8 octant pieces of the sphere and 24
        // quarter-plane pieces (inside and outside it); 6 half-axis chains
        // split by the sphere (12) and 12 quarter circles; the centre, the
        // 6 axis points on the sphere and the 6 on the box.
        Case {
            name: "planes and sphere IA",
            functions: PLANES_AND_SPHERE,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 32), ("chains", 24), ("corners", 13), ("cells", 16)],
        },
        // The same sphere twice, and scaled by 2 (the reference's sphere is
        // `r - |p - c|`; radius and centre scaled): same zero set.
        Case {
            name: "duplicated sphere IA",
            functions: r#"[{"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("cells", 2), ("shells", 2)],
        },
        // Two materials equal everywhere: no interface at all.
        Case {
            name: "tied materials MI",
            functions: r#"[{"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#,
            mode: Mode::Mi,
            n: 4,
            sparse_holds: true,
            streams: true,
            counts: &[("vertices", 0), ("faces", 0), ("patches", 0), ("components", 0), ("cells", 1)],
        },
        // x and 2x: planes are normalised wherever they are read, so the two
        // functions are one (the reference does the same): no interface.
        Case {
            name: "plane and doubled plane MI",
            functions: r#"[{"type": "plane", "point": [0, 0, 0], "normal": [1, 0, 0]},
                           {"type": "plane", "point": [0, 0, 0], "normal": [2, 0, 0]}]"#,
            mode: Mode::Mi,
            n: 4,
            sparse_holds: true,
            streams: true,
            counts: &[("vertices", 0), ("faces", 0), ("patches", 0), ("cells", 1)],
        },
        Case {
            name: "round spheres MI with a tied copy",
            // The same interface as without the copy.
            functions: r#"[
 {"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
 {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
 {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5},
 {"type": "sphere", "center": [0, 0, 0.5], "radius": 0.5},
 {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#,
            mode: Mode::Mi,
            n: 16,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 6), ("chains", 4), ("corners", 5), ("cells", 4), ("components", 1)],
        },
        // A plane through grid vertices: its faces lie in tet faces.
        Case {
            name: "plane through nodes IA",
            functions: r#"[{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}]"#,
            mode: Mode::Ia,
            n: 6,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 1), ("cells", 2), ("chains", 0)],
        },
        // Two spheres tangent at a grid vertex (the origin).
        Case {
            name: "tangent spheres IA",
            functions: r#"[{"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5}]"#,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true, // shells linked at the contact point
            streams: true,
            counts: &[("patches", 2), ("cells", 3)],
        },
        // A sphere inside another, tangent at grid vertex (0.5, 0, 0).
        Case {
            name: "internally tangent spheres IA",
            functions: r#"[{"type": "sphere", "center": [0, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0.25, 0, 0], "radius": 0.25}]"#,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 2), ("cells", 3)],
        },
        // Three spheres pairwise tangent at grid vertices, and a fourth
        // crossing one of them (its sheet has a chain).
        Case {
            name: "chain of tangent spheres IA",
            functions: r#"[{"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0, 0.5, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0.5, 0.5, 0.5], "radius": 0.3}]"#,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[],
        },
        // A diagonal plane through grid vertex 0, the sink of ray shooting,
        // cutting a sphere through grid vertices: two half-discs of the plane
        // (inside and outside the ball) and two hemispheres meeting along one
        // closed circle; four cells.
        Case {
            name: "plane through the sink IA",
            functions: r#"[{"type": "plane", "point": [-1, -1, -1], "normal": [1, -1, 0]},
                           {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]"#,
            mode: Mode::Ia,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 4), ("chains", 1), ("corners", 0), ("shells", 4), ("cells", 4)],
        },
        // MI: materials 1 and 2 (x - 0.25 and -(x + 0.75)) tie on the whole
        // grid plane x = -0.25, and a ball (material 0) wins on a disc of it,
        // so only part of some tet faces is interface, and three materials
        // tie at grid vertices on the disc's rim. The rim leaves the box
        // twice: a long and a short arc (2 chains, 4 corners), the plane
        // outside the disc in two patches, and the ball's two sides.
        Case {
            name: "tie over part of a tet face MI",
            functions: r#"[{"type": "sphere", "center": [-0.75, 0.5, 0.5], "radius": 0.25},
                           {"type": "plane", "point": [0.25, 0.25, 0.5], "normal": [1, 0, 0]},
                           {"type": "plane", "point": [-0.75, 0, -1], "normal": [-2, 0, 0]}]"#,
            mode: Mode::Mi,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 4), ("chains", 2), ("corners", 4), ("shells", 3), ("cells", 3)],
        },
        // MI: two tangent balls in a background (three materials tie at the
        // contact point).
        Case {
            name: "tangent spheres MI",
            functions: r#"[{"type": "sphere", "center": [-0.5, 0, 0], "radius": 0.5},
                           {"type": "sphere", "center": [0.5, 0, 0], "radius": 0.5},
                           {"type": "zero"}]"#,
            mode: Mode::Mi,
            n: 8,
            sparse_holds: true,
            streams: true,
            counts: &[("patches", 2), ("cells", 3)],
        },
    ]
}

fn options(mode: Mode) -> NetworkOptions {
    let mut o = NetworkOptions::new(mode);
    o.block = 4; // several blocks even on small grids
    o
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap()
}

/// A scratch file holding `text`.
fn scratch(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("septa-one-answer-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

struct Count(usize);

impl StreamSink for Count {
    fn block(&mut self, b: &StreamBlock) -> std::io::Result<()> {
        self.0 += b.num_polygons();
        Ok(())
    }
}

fn run(job: &Job, mode: Mode, dense: bool, threads: usize) -> (Network, bool) {
    let (net, stats) = pool(threads).install(|| job.run(&options(mode), dense)).unwrap();
    (net, stats.is_some_and(|s| s.dense_fallback))
}

#[test]
fn every_path_gives_one_answer_on_round_inputs() {
    for case in cases() {
        let what = case.name;
        let list = scratch(&format!("{}.json", what.replace(' ', "-")), case.functions);
        let over = GridOverride { resolution: Some(case.n), ..Default::default() };
        let job = Job::load(list.to_str().unwrap(), &over).unwrap();
        // The reference: the dense path, one thread.
        let (dense, _) = run(&job, case.mode, true, 1);
        let counts: std::collections::HashMap<_, _> = dense.counts().into_iter().collect();
        for (k, v) in case.counts {
            assert_eq!(counts[k], *v, "{what}: {k} (all: {counts:?})");
        }
        // Sparse, 1 and 2 threads: the same bytes, and the path it must take.
        for threads in [1, 2] {
            let (sparse, fell_back) = run(&job, case.mode, false, threads);
            assert_same_network(&dense, &sparse, &format!("{what}: sparse, {threads} threads"));
            assert_eq!(!fell_back, case.sparse_holds, "{what}: sparse path fell back = {fell_back}");
            let (d2, _) = run(&job, case.mode, true, threads);
            assert_same_network(&dense, &d2, &format!("{what}: dense, {threads} threads"));
        }
        // A scene file with the same functions: the same network.
        let scene = format!(
            r#"{{"grid": {{"resolution": {}, "bounds": [[-1, -1, -1], [1, 1, 1]]}}, "mode": "{}", "functions": {}}}"#,
            case.n,
            if case.mode == Mode::Ia { "ia" } else { "mi" },
            case.functions
        );
        let scene_path = scratch(&format!("{}-scene.json", what.replace(' ', "-")), &scene);
        let from_scene = Job::load(scene_path.to_str().unwrap(), &GridOverride::default()).unwrap();
        assert_eq!(from_scene.mode, Some(case.mode));
        let (s, _) = run(&from_scene, case.mode, false, 2);
        assert_same_network(&dense, &s, &format!("{what}: scene file"));
        // The stream with topology: accepted where it must be, same counts.
        let (g, f) = job.box_formulas().unwrap();
        let mut sink = Count(0);
        match stream_topology(g, f, &options(case.mode), 2, &mut sink) {
            Ok((stats, summary)) => {
                assert!(case.streams, "{what}: streamed, but the case expects a refusal");
                assert_eq!(summary.counts(), dense.counts(), "{what}: streamed topology");
                assert_eq!(sink.0, dense.num_faces(), "{what}: streamed faces");
                assert_eq!(stats.vertices as usize, dense.points.len(), "{what}: streamed vertices");
            }
            Err(e) => {
                assert!(!case.streams, "{what}: the stream refused: {e}");
                let m = e.to_string();
                assert!(m.contains("block ") && (m.contains("tet face") || m.contains("ray")), "{what}: {m}");
            }
        }
    }
}

#[test]
fn reordered_functions_give_the_same_network_up_to_labels() {
    // Function order never changes the combinatorics: counts agree on the
    // round spheres, reversed (dense and sparse).
    let list: Vec<serde_json::Value> = serde_json::from_str(ROUND_SPHERES).unwrap();
    let reversed: Vec<serde_json::Value> = list.iter().rev().cloned().collect();
    let over = GridOverride { resolution: Some(16), ..Default::default() };
    let a = Job::load(scratch("fwd.json", ROUND_SPHERES).to_str().unwrap(), &over).unwrap();
    let text = serde_json::to_string(&reversed).unwrap();
    let b = Job::load(scratch("rev.json", &text).to_str().unwrap(), &over).unwrap();
    for mode in [Mode::Ia, Mode::Mi] {
        let (na, _) = run(&a, mode, false, 2);
        let (nb, _) = run(&b, mode, true, 1);
        assert_eq!(na.counts(), nb.counts(), "{mode:?}");
    }
}
