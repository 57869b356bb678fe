//! CSG trees of the adaptive-grid paper's data (`load_csg_tree`, and
//! `"solid": {"csg_tree": ..}` in a scene), with Septa's sign convention
//! (positive inside: `Intersection` is inside both), and its grid files.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::{load_csg_tree, Expr, Scene};

fn adaptive() -> std::path::PathBuf {
    crate::common::shared_data().join("adaptive")
}

fn tree(rel: &str, n: usize) -> Result<Expr, septa::scene::SceneError> {
    tree_as(rel, n, false)
}

fn tree_as(rel: &str, n: usize, negative_inside: bool) -> Result<Expr, septa::scene::SceneError> {
    let path = adaptive().join(rel);
    load_csg_tree(&std::fs::read_to_string(&path).unwrap(), &path.display().to_string(), n, negative_inside)
}

#[test]
fn every_anchor_tree_reads_with_its_functions() {
    for (rel, n) in [
        ("Figure1/10-wikiBall-tree.json", 10),
        ("Figure14/figure14_tree.json", 8),
        ("Figure20/csg_examples_1_tree.json", 4),
        ("Figure21/csg_examples_3_tree.json", 20),
        ("Figure22/doghead_800_int_tree.json", 2),
        ("csg_sign_test/tree_intersection.json", 2),
    ] {
        let e = tree(rel, n).unwrap_or_else(|e| panic!("{rel}: {e}"));
        let mut used = std::collections::BTreeSet::new();
        e.functions(&mut used);
        assert!(!used.is_empty() && *used.iter().last().unwrap() < n, "{rel}: {used:?}");
    }
    // Figure 22b's tree names a function its config (one RBF) lacks.
    let e = tree("Figure22/doghead_800_int_tree.json", 1).unwrap_err();
    assert!(e.message.contains("function 2 does not exist") && e.path.to_string() == "[0].elements[1]", "{e}");
}

#[test]
fn trees_mean_what_they_say() {
    // Figure 20: node 1 = 2 & 3, 2 = !f1, 3 = f2 & 4, 4 = f3 & f4. Positive
    // inside: outside the torus, inside the three cylinders; as the paper's
    // program reads it (in where negative): inside the torus, outside the
    // cylinders (its figure: a torus drilled by near-tangent cylinders).
    let e = tree("Figure20/csg_examples_1_tree.json", 4).unwrap();
    let en = tree_as("Figure20/csg_examples_1_tree.json", 4, true).unwrap();
    // Figure 1 (the wiki ball): 1 = 2 & 8, 2 = 3 & 14, 3 = -1 & 4, ...,
    // 7 = -5 & -6, 8 = !9, 9 = 11 | 10, 10 = 12 | 13, 11..14 = !f7 .. !f10.
    // Positive inside this is outside all six faces at once: empty. Read as
    // the paper's program does: inside the cube (planes with outward
    // normals), inside the sphere, outside the three cylinders.
    let ball = tree("Figure1/10-wikiBall-tree.json", 10).unwrap();
    let balln = tree_as("Figure1/10-wikiBall-tree.json", 10, true).unwrap();
    let sign = tree("csg_sign_test/tree_intersection.json", 2).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut ball_inside = 0;
    for _ in 0..8000 {
        let s: Vec<bool> = (0..10).map(|_| rng.gen_bool(0.5)).collect();
        let at = |i: usize| s[i];
        assert_eq!(e.eval(&at), !s[0] && s[1] && s[2] && s[3]);
        assert_eq!(en.eval(&at), s[0] && !s[1] && !s[2] && !s[3]);
        assert_eq!(ball.eval(&at), (0..6).all(|i| s[i]) && !s[9] && s[6] && s[7] && s[8]);
        let inside = (0..6).all(|i| !s[i]) && s[9] && !(s[6] || s[7] || s[8]);
        assert_eq!(balln.eval(&at), inside);
        ball_inside += inside as usize;
        assert_eq!(sign.eval(&at), s[0] && s[1], "Intersection is inside both (positive inside)");
    }
    assert!(ball_inside > 0);
}

#[test]
fn bad_trees_are_named() {
    let bad = [
        (r#"[{"type": "Intersection", "elements": [2, -1]}, {"type": "Union", "elements": [1, -1]}]"#, "cycle", "[0]"),
        (r#"[{"type": "Intersection", "elements": [3, -1]}]"#, "node 3 does not exist", "[0].elements[0]"),
        (r#"[{"type": "Intersection", "elements": [-1, -4]}]"#, "function 4 does not exist", "[0].elements[1]"),
        (r#"[{"type": "Xor", "elements": [-1, -2]}]"#, "unknown CSG operation `Xor`", "[0].type"),
        (r#"[{"type": "Union", "elements": [-1]}]"#, "expected 2 elements", "[0].elements"),
        (r#"[{"type": "Union", "elements": [-1, 0.5]}]"#, "node number", "[0].elements[1]"),
        (r#"[]"#, "empty CSG tree", "(document)"),
    ];
    for (text, what, path) in bad {
        let e = load_csg_tree(text, "t.json", 3, false).unwrap_err();
        assert!(e.message.contains(what) && e.path.to_string() == path, "{text}: {e}");
        assert!(e.to_string().starts_with("t.json:1:"), "{e}");
    }
}

#[test]
fn a_scene_runs_the_anchors_csg_files() {
    // The sign test of shared/data/adaptive: the intersection of two
    // spheres is a lens, one closed surface (Euler characteristic 2).
    let dir = adaptive().join("csg_sign_test");
    let text = r#"{"grid": {"resolution": [24], "bbox_min": [0, 0, 0], "bbox_max": [1, 1, 1]},
        "functions": "two_spheres.json", "solid": {"csg_tree": "tree_intersection.json"}}"#;
    let s = Scene::from_json(text, "lens.json", Some(&dir)).unwrap();
    assert_eq!((s.grid.resolution, s.grid.split), ([24; 3], 6));
    let r = region_surfaces(&s, &RegionOptions::default()).unwrap();
    let lens: Vec<_> = r.surfaces.iter().map(|x| (x.regions, x.euler, x.boundary_loops)).collect();
    assert_eq!(lens, vec![([0, 1], 2, 0)]);
    // The union instead (an inline tree): also one closed surface, larger.
    let union = text.replace(r#""tree_intersection.json""#, r#"[{"type": "Union", "elements": [-1, -2]}]"#);
    let u = region_surfaces(&Scene::from_json(&union, "union.json", Some(&dir)).unwrap(), &RegionOptions::default())
        .unwrap();
    assert_eq!(u.surfaces.len(), 1);
    assert!(u.surfaces[0].faces > r.surfaces[0].faces);
    // The grid as the anchor's own file.
    let text = text.replace(r#"{"resolution": [24], "bbox_min": [0, 0, 0], "bbox_max": [1, 1, 1]}"#, r#""grid4.json""#);
    let s = Scene::from_json(&text, "lens.json", Some(&dir)).unwrap();
    assert_eq!((s.grid.resolution, s.grid.bounds, s.grid.split), ([4; 3], [[0.0; 3], [1.0; 3]], 6));
    // A tree naming a missing function is named where it is used.
    let bad = r#"{"grid": "grid4.json", "functions": "two_spheres.json",
        "solid": {"csg_tree": [{"type": "Union", "elements": [-1, -3]}]}}"#;
    let e = Scene::from_json(bad, "bad.json", Some(&dir)).unwrap_err();
    assert!(
        e.message.contains("function 3 does not exist") && e.path.to_string() == "solid.csg_tree[0].elements[1]",
        "{e}"
    );
    // Read as the paper's program does, the same tree is the outside of both.
    let neg = r#"{"grid": {"resolution": [24], "bbox_min": [0, 0, 0], "bbox_max": [1, 1, 1]},
        "functions": "two_spheres.json", "solid": {"csg_tree": "tree_intersection.json", "inside": "negative"}}"#;
    let n =
        region_surfaces(&Scene::from_json(neg, "neg.json", Some(&dir)).unwrap(), &RegionOptions::default()).unwrap();
    assert_eq!(n.surfaces.len(), 1);
    assert_eq!(n.surfaces[0].faces, u.surfaces[0].faces, "the union's boundary");
    let e = Scene::from_json(&neg.replace("negative", "inward"), "neg.json", Some(&dir)).unwrap_err();
    assert_eq!(e.path.to_string(), "solid.inside", "{e}");
}
