//! `scene_json` (`septa regions --print`) is the inverse of the scene
//! reader: every built-in scene prints, reads back, and prints the same
//! again; the printed scenes give the same surfaces and curves.
use septa::regions::{region_surfaces, RegionOptions};
use septa::scene::{builtin, scene_json, scene_text, Scene};

#[test]
fn every_builtin_prints_and_reads_back() {
    for (name, _) in builtin::list() {
        let scene = builtin::get(name).unwrap();
        let printed = scene_json(&scene).unwrap_or_else(|e| panic!("{name}: {e}"));
        let text = scene_text(&scene).unwrap();
        // The text to edit is the same document.
        assert_eq!(serde_json::from_str::<serde_json::Value>(&text).unwrap(), printed, "{name}");
        let back = Scene::from_json(&text, name, None).unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(back.names, scene.names, "{name}");
        assert_eq!(back.functions.len(), scene.functions.len(), "{name}");
        assert_eq!(back.grid.resolution, scene.grid.resolution, "{name}");
        // The same again, but for the last bit of a re-normalized direction.
        assert!(close(&scene_json(&back).unwrap(), &printed), "{name}: printing the read scene differs");
    }
}

#[test]
fn printed_scenes_give_the_same_shapes() {
    for name in ["sphere-plane-hole", "cad-part"] {
        let a = region_surfaces(&builtin::get(name).unwrap(), &RegionOptions::default()).unwrap();
        let text = scene_json(&builtin::get(name).unwrap()).unwrap().to_string();
        let b = region_surfaces(&Scene::from_json(&text, name, None).unwrap(), &RegionOptions::default()).unwrap();
        let topo = |r: &septa::regions::RegionSurfaces| {
            (
                r.surfaces.iter().map(|s| (s.regions, s.faces, s.euler, s.boundary_loops)).collect::<Vec<_>>(),
                r.curves.iter().map(|c| (c.regions.clone(), c.vertices.len(), c.closed)).collect::<Vec<_>>(),
            )
        };
        assert_eq!(topo(&a), topo(&b), "{name}");
        assert!(!a.surfaces.is_empty());
    }
}

/// Equal JSON, numbers within 4 units in the last place.
fn close(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    use serde_json::Value::*;
    match (a, b) {
        (Number(x), Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            x == y || (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(y.abs())
        }
        (Array(x), Array(y)) => x.len() == y.len() && x.iter().zip(y).all(|(x, y)| close(x, y)),
        (Object(x), Object(y)) => x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| close(v, w))),
        _ => a == b,
    }
}
