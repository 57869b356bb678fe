//! Scene files (see [`Scene`]).

use std::collections::BTreeSet;
use std::path::Path;

use serde_json::Value;

use super::error::{err, locate, JsonPath, Located, SceneError};
use super::grid_spec::{grid, GridSpec};
use super::primitive::Primitive;
use super::region_rule::{Expr, Interest, RegionId, RegionRule, Rule};
use super::spec::{array, primitive, vec3, Ctx, Obj};

pub use crate::complex::Mode;

/// A scene: what to partition and which walls to return: a grid, named
/// functions, a mode, region rules and the surfaces and curves of interest
///. Its JSON form:
///
/// ```json
/// {"grid": {"resolution": 33, "bounds": [[-1,-1,-1],[1,1,1]], "split": 5},
///  "mode": "ia",
///  "functions": [{"name": "big", "type": "sphere", "center": [0,0,0], "radius": 0.6},
///                {"name": "hole", "type": "sphere", "center": [0,0,0.6], "radius": 0.3}],
///  "regions": [{"when": "hole", "region": 1}, {"when": "big", "region": 2}, {"region": 0}],
///  "surfaces": [[0, 2]], "curves": [[0, 1, 2]]}
/// ```
///
/// `regions` may instead be `{"rules": [...], "otherwise": R}`, or replaced
/// by `"solid": "EXPR"` (CSG: region 1 inside, 0 outside). Conditions are
/// [`Expr`] text (`"a & !b"`, `"box - hole"`) or trees (`{"union": [..]}`,
/// `{"intersection": [..]}`, `{"difference": [a, b]}`, `{"complement": e}`).
/// A function without `name` is named by its index. `functions` may also be
/// the path of a reference implementation function file.
/// Reference implementation config files (`gridResolution`, `gridBbox`,
/// `funcFile`) load too, as IA scenes without a region rule.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The grid.
    pub grid: GridSpec,
    /// IA or MI.
    pub mode: Mode,
    /// Function names (unnamed functions are named by their index).
    pub names: Vec<String>,
    /// The functions, in order.
    pub functions: Vec<Primitive>,
    /// Cell label -> region.
    pub regions: RegionRule,
    /// Region pairs and triples of interest.
    pub interest: Interest,
    /// Names of regions (`"region_names": {"1": "part"}`; a `solid` is
    /// `inside` (1) and `outside` (0) unless named otherwise).
    pub region_names: std::collections::BTreeMap<RegionId, String>,
}

impl Scene {
    /// The names every result writer uses (`io::Names`): the functions' and the regions'.
    pub fn result_names(&self) -> crate::io::Names {
        crate::io::Names { functions: self.names.clone(), regions: self.region_names.clone() }
    }

    /// Index of the function called `name` (or whose index `name` is).
    pub fn function_index(&self, name: &str) -> Option<usize> {
        resolve(&self.names, name)
    }

    /// Read a scene from a file, or `builtin:NAME`.
    pub fn load(path: &str) -> Result<Scene, SceneError> {
        if let Some(name) = path.strip_prefix("builtin:") {
            return super::builtin::get(name).ok_or_else(|| SceneError {
                file: path.to_string(),
                line: 0,
                column: 0,
                path: JsonPath::default(),
                message: format!(
                    "no built-in scene `{name}` (known: {})",
                    super::builtin::list().iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
                ),
            });
        }
        let text = crate::io::read_input_text(Path::new(path)).map_err(|e| SceneError {
            file: path.to_string(),
            line: 0,
            column: 0,
            path: JsonPath::default(),
            message: format!("cannot read: {e}"),
        })?;
        if path.ends_with(".toml") {
            return Scene::from_toml(&text, path, Path::new(path).parent());
        }
        Scene::from_json(&text, path, Path::new(path).parent())
    }

    /// Parse a TOML scene: the fields of the JSON form (`mode`, `[grid]`,
    /// `[[functions]]`, `regions`, `surfaces`, `curves`, ...), read into
    /// the same value tree and checked by the same code; errors name the
    /// TOML line and column.
    ///
    /// ```
    /// let text = r#"
    /// mode = "ia"
    /// [grid]
    /// resolution = 16
    /// bounds = [[-1, -1, -1], [1, 1, 1]]
    /// [[functions]]
    /// name = "ball"
    /// type = "sphere"
    /// center = [0, 0, 0]
    /// radius = 0.5
    /// "#;
    /// let scene = septa::scene::Scene::from_toml(text, "ball.toml", None).unwrap();
    /// assert_eq!(scene.functions.len(), 1);
    /// ```
    pub fn from_toml(text: &str, file: &str, base_dir: Option<&Path>) -> Result<Scene, SceneError> {
        let t: toml::Value = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| super::error::line_column(text, s.start));
            SceneError { file: file.to_string(), line, column, path: JsonPath::default(), message: e.message().into() }
        })?;
        let v = serde_json::to_value(&t).map_err(|e| SceneError {
            file: file.to_string(),
            line: 0,
            column: 0,
            path: JsonPath::default(),
            message: format!("not a scene: {e}"),
        })?;
        scene(&v, base_dir).map_err(|l| {
            let (line, column) = super::error::locate_toml(text, &l.path).unwrap_or((0, 0));
            SceneError { file: file.to_string(), line, column, path: l.path, message: l.message }
        })
    }

    /// Parse scene JSON `text`; `file` names it in errors and `base_dir`
    /// resolves relative paths inside it.
    ///
    /// ```
    /// use septa::scene::Scene;
    /// let text = r#"{"grid": {"resolution": 8, "bounds": [[-1,-1,-1],[1,1,1]]},
    ///   "functions": [{"type": "sphere", "center": [0,0,0], "radius": -1}]}"#;
    /// let e = Scene::from_json(text, "s.json", None).unwrap_err();
    /// assert_eq!((e.line, e.path.to_string()), (2, "functions[0].radius".to_string()));
    /// assert!(e.to_string().starts_with("s.json:2:"));
    /// ```
    pub fn from_json(text: &str, file: &str, base_dir: Option<&Path>) -> Result<Scene, SceneError> {
        let v: Value = super::strict_json::parse(text).map_err(|e| SceneError {
            file: file.to_string(),
            line: e.line(),
            column: e.column(),
            path: JsonPath::default(),
            message: e.to_string(),
        })?;
        scene(&v, base_dir).map_err(|l| {
            let (line, column) = locate(text, &l.path).unwrap_or((0, 0));
            SceneError { file: file.to_string(), line, column, path: l.path, message: l.message }
        })
    }
}

/// Read a reference implementation function file (a JSON list of
/// primitives, or `{"input": [...]}`), with the reference's meaning of a
/// negative sphere radius (unsigned distance). A key the reader does not
/// use (`"negate": true`: the reference program ignores it too) is a
/// warning printed to standard error ([`load_function_list_warnings`]
/// returns them instead); a key given twice is an error.
pub fn load_function_list(text: &str, file: &str, base_dir: Option<&Path>) -> Result<Vec<Primitive>, SceneError> {
    let (functions, warnings) = load_function_list_warnings(text, file, base_dir)?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    Ok(functions)
}

/// [`load_function_list`] with its warnings (keys not used, each naming
/// the file, line and key) returned instead of printed.
pub fn load_function_list_warnings(
    text: &str,
    file: &str,
    base_dir: Option<&Path>,
) -> Result<(Vec<Primitive>, Vec<SceneError>), SceneError> {
    let v: Value = super::strict_json::parse(text).map_err(|e| SceneError {
        file: file.to_string(),
        line: e.line(),
        column: e.column(),
        path: JsonPath::default(),
        message: e.to_string(),
    })?;
    let ctx = Ctx::new(base_dir, true);
    let located = |l: Located| {
        let (line, column) = locate(text, &l.path).unwrap_or((0, 0));
        SceneError { file: file.to_string(), line, column, path: l.path, message: l.message }
    };
    let functions = function_list(&v, &JsonPath::default(), &ctx).map_err(located)?;
    Ok((functions, ctx.warnings.into_inner().into_iter().map(located).collect()))
}

fn function_list(v: &Value, path: &JsonPath, ctx: &Ctx) -> Result<Vec<Primitive>, Located> {
    let (v, path) = match v.get("input") {
        Some(inner) if v.is_object() => (inner, path.key("input")),
        _ => (v, path.clone()),
    };
    let a = array(v, &path)?;
    a.iter().enumerate().map(|(i, f)| primitive(f, &path.index(i), ctx)).collect()
}

fn resolve(names: &[String], name: &str) -> Option<usize> {
    names.iter().position(|n| n == name).or_else(|| name.parse::<usize>().ok().filter(|&i| i < names.len()))
}

/// `"solid": {"csg_tree": FILE or [nodes], "inside": "positive" |
/// "negative"}`: a CSG tree of the adaptive-grid paper (`csg_tree.rs`; the
/// paper's own figures read with `"inside": "negative"`).
fn solid_tree(s: &Value, path: &JsonPath, n: usize, base_dir: Option<&Path>) -> Option<Result<Expr, Located>> {
    let m = s.as_object()?;
    let t = m.get("csg_tree")?;
    let p = path.key("csg_tree");
    if let Some(k) = m.keys().find(|k| *k != "csg_tree" && *k != "inside") {
        return Some(err(&path.key(k), format!("unknown key `{k}` (csg_tree, inside)")));
    }
    let negative = match m.get("inside").map(|v| v.as_str()) {
        None | Some(Some("positive")) => false,
        Some(Some("negative")) => true,
        _ => return Some(err(&path.key("inside"), "inside is `positive` or `negative`")),
    };
    Some(match t {
        Value::String(file) => {
            let full = base_dir.map_or_else(|| Path::new(file).to_path_buf(), |d| d.join(file));
            crate::io::read_input_text(&full)
                .or_else(|e| err(&p, format!("cannot read {}: {e}", full.display())))
                .and_then(|text| {
                    super::csg_tree::load_csg_tree(&text, &full.display().to_string(), n, negative)
                        .or_else(|e| err(&p, e.to_string()))
                })
        }
        tree => super::csg_tree::csg_tree(tree, &p, n, negative),
    })
}

fn expr(v: &Value, path: &JsonPath, names: &[String]) -> Result<Expr, Located> {
    match v {
        Value::String(s) => Expr::parse(s, &|n: &str| resolve(names, n)).or_else(|m| err(path, m)),
        Value::Object(m) if m.len() == 1 => {
            let (k, inner) = m.iter().next().unwrap();
            let p = path.key(k);
            let list = |inner: &Value| -> Result<Vec<Expr>, Located> {
                let a = array(inner, &p)?;
                if a.is_empty() {
                    return err(&p, "needs at least one operand");
                }
                a.iter().enumerate().map(|(i, e)| expr(e, &p.index(i), names)).collect()
            };
            match k.as_str() {
                "union" => Ok(Expr::Or(list(inner)?)),
                "intersection" => Ok(Expr::And(list(inner)?)),
                "complement" => Ok(Expr::Not(Box::new(expr(inner, &p, names)?))),
                "difference" => {
                    let mut l = list(inner)?;
                    let first = l.remove(0);
                    Ok(super::region_rule::difference(first, l))
                }
                "function" => match inner.as_str().and_then(|n| resolve(names, n)) {
                    Some(i) => Ok(Expr::Func(i)),
                    None => err(&p, format!("unknown function {inner}")),
                },
                _ => err(&p, format!("unknown operator `{k}` (union, intersection, difference, complement, function)")),
            }
        }
        _ => err(
            path,
            "expected an expression string or {\"union\"|\"intersection\"|\"difference\"|\"complement\": ...}",
        ),
    }
}

fn region_id(v: &Value, path: &JsonPath) -> Result<RegionId, Located> {
    v.as_i64().map_or_else(|| err(path, "a region is an integer"), Ok)
}

fn rules(v: &Value, path: &JsonPath, names: &[String]) -> Result<RegionRule, Located> {
    let (list, lp, mut otherwise) = match v {
        Value::Object(_) => {
            let o = Obj::new(v, path)?;
            o.mark_all(&["rules", "otherwise"]);
            o.finish()?;
            let other =
                if o.has("otherwise") { Some(region_id(o.get("otherwise")?, &path.key("otherwise"))?) } else { None };
            (o.get("rules")?, path.key("rules"), other)
        }
        _ => (v, path.clone(), None),
    };
    let mut out = Vec::new();
    for (i, r) in array(list, &lp)?.iter().enumerate() {
        let o = Obj::new(r, &lp.index(i))?;
        o.mark_all(&["region", "when"]);
        o.finish()?;
        let region = region_id(o.get("region")?, &o.path.key("region"))?;
        if !o.has("when") {
            // A catch-all ends the list (later rules could never match).
            otherwise.get_or_insert(region);
            break;
        }
        out.push(Rule { when: expr(o.get("when")?, &o.path.key("when"), names)?, region });
    }
    Ok(RegionRule::Rules { rules: out, otherwise: otherwise.unwrap_or(0) })
}

fn tuples<const N: usize>(
    v: &Value,
    path: &JsonPath,
    known: &BTreeSet<RegionId>,
) -> Result<Vec<[RegionId; N]>, Located> {
    let mut out = Vec::new();
    for (i, t) in array(v, path)?.iter().enumerate() {
        let p = path.index(i);
        let a = array(t, &p)?;
        if a.len() != N {
            return err(&p, format!("expected {N} regions"));
        }
        let mut r = [0; N];
        for j in 0..N {
            r[j] = region_id(&a[j], &p.index(j))?;
            if !known.is_empty() && !known.contains(&r[j]) {
                return err(&p.index(j), format!("region {} is never produced by the region rule", r[j]));
            }
        }
        out.push(r);
    }
    Ok(out)
}

fn scene(v: &Value, base_dir: Option<&Path>) -> Result<Scene, Located> {
    let root = JsonPath::default();
    if v.is_array() {
        return err(
            &root,
            "a scene is an object with `grid` and `functions` (this looks like a reference function list)",
        );
    }
    let o = Obj::new(v, &root)?;
    if o.has("funcFile") {
        return reference_config(&o, base_dir);
    }
    let grid = grid(o.get("grid")?, &root.key("grid"), base_dir)?;
    // a scene's keys: anything else (a misspelt `surface`) is an error
    o.mark_all(&["grid", "mode", "functions", "regions", "solid", "surfaces", "curves", "features", "region_names"]);
    o.finish()?;
    let mode = match o.opt("mode").map(|m| m.as_str()) {
        None | Some(Some("ia")) => Mode::Ia,
        Some(Some("mi")) => Mode::Mi,
        _ => return err(&root.key("mode"), "mode must be \"ia\" or \"mi\""),
    };
    let fp = root.key("functions");
    let ctx = Ctx::new(base_dir, false);
    let (functions, names) = match o.get("functions")? {
        Value::String(file) => {
            let full = base_dir.map_or_else(|| Path::new(file).to_path_buf(), |d| d.join(file));
            let text = crate::io::read_input_text(&full)
                .or_else(|e| err(&fp, format!("cannot read {}: {e}", full.display())))?;
            let f = load_function_list(&text, &full.display().to_string(), full.parent())
                .or_else(|e| err(&fp, e.to_string()))?;
            let names = (0..f.len()).map(|i| i.to_string()).collect();
            (f, names)
        }
        list => {
            let a = array(list, &fp)?;
            let mut names: Vec<String> = Vec::new();
            let mut functions = Vec::new();
            for (i, f) in a.iter().enumerate() {
                let p = fp.index(i);
                functions.push(primitive(f, &p, &ctx)?);
                let name = match f.get("name") {
                    None => i.to_string(),
                    Some(Value::String(s)) => {
                        let ok = !s.is_empty() && s.chars().all(|c| c.is_alphanumeric() || c == '_' || c == '.');
                        if !ok || (s.parse::<usize>().is_ok() && *s != i.to_string()) {
                            return err(&p.key("name"), format!("bad function name `{s}` (letters, digits, `_`, `.`; a number only if it is the function's own index)"));
                        }
                        if names.contains(s) {
                            return err(&p.key("name"), format!("duplicate function name `{s}`"));
                        }
                        s.clone()
                    }
                    Some(_) => return err(&p.key("name"), "a name is a string"),
                };
                names.push(name);
            }
            (functions, names)
        }
    };
    if functions.is_empty() {
        return err(&fp, "no functions");
    }
    let regions = match (o.opt("regions"), o.opt("solid")) {
        (Some(_), Some(_)) => return err(&root.key("solid"), "give `regions` or `solid`, not both"),
        (Some(r), None) => rules(r, &root.key("regions"), &names)?,
        (None, Some(s)) => match solid_tree(s, &root.key("solid"), functions.len(), base_dir) {
            Some(tree) => RegionRule::solid(tree?),
            None => RegionRule::solid(expr(s, &root.key("solid"), &names)?),
        },
        (None, None) => {
            if mode == Mode::Ia && functions.len() > 62 {
                return err(&fp, "more than 62 functions need a `regions` rule");
            }
            RegionRule::Identity
        }
    };
    let known = match (&regions, mode) {
        (RegionRule::Identity, Mode::Mi) => (0..functions.len() as RegionId).collect(),
        _ => regions.regions(),
    };
    let surfaces = match o.opt("surfaces") {
        None => None,
        Some(Value::String(s)) if s == "all" => None,
        Some(s) => Some(tuples::<2>(s, &root.key("surfaces"), &known)?),
    };
    let curves = match o.opt("curves") {
        None => None,
        Some(Value::String(s)) if s == "all" => None,
        Some(c) => Some(tuples::<3>(c, &root.key("curves"), &known)?),
    };
    let features = match o.opt("features") {
        None => true,
        Some(Value::Bool(b)) => *b,
        Some(_) => return err(&root.key("features"), "`features` is true or false"),
    };
    let mut interest = Interest::new(surfaces.as_deref(), curves.as_deref().unwrap_or(&[]));
    if curves.is_none() {
        interest.curves = None;
    }
    interest.features = features;
    let mut region_names = std::collections::BTreeMap::new();
    if o.has("solid") {
        region_names.insert(0, "outside".to_string());
        region_names.insert(1, "inside".to_string());
    }
    if let Some(v) = o.opt("region_names") {
        let p = root.key("region_names");
        let Some(map) = v.as_object() else {
            return err(&p, "`region_names` is an object: {\"1\": \"part\", \"0\": \"air\"}");
        };
        for (k, name) in map {
            let Ok(r) = k.trim().parse::<RegionId>() else {
                return err(&p.key(k), format!("`{k}` is not a region number"));
            };
            if !known.is_empty() && !known.contains(&r) {
                return err(&p.key(k), format!("region {r} is never produced by the region rule"));
            }
            match name.as_str() {
                Some(n) if !n.trim().is_empty() => region_names.insert(r, n.to_string()),
                _ => return err(&p.key(k), "a region name is a non-empty string"),
            };
        }
    }
    Ok(Scene { grid, mode, names, functions, regions, interest, region_names })
}

/// A reference implementation config (`{"gridResolution": R, "gridBbox":
/// [[..],[..]], "funcFile": PATH, ...}`): an IA scene over its grid with
/// the function file's primitives and no region rule (callers switch the
/// mode for the reference's `material_interface` runs). Its other keys
/// (`outputDir`, `useLookup`, ...) are the reference's run options.
fn reference_config(o: &Obj, base_dir: Option<&Path>) -> Result<Scene, Located> {
    let root = JsonPath::default();
    if o.has("tetMeshFile") {
        return err(
            &root.key("tetMeshFile"),
            "a tet mesh config has no box grid; give the tet mesh to the IA / MI pipeline directly",
        );
    }
    let r = o.get("gridResolution")?;
    let rp = root.key("gridResolution");
    let n = match r.as_i64() {
        Some(n) if (1..=1 << 20).contains(&n) => n as usize,
        _ => return err(&rp, format!("empty grid: resolution {r}")),
    };
    let bp = root.key("gridBbox");
    let b = array(o.get("gridBbox")?, &bp)?;
    if b.len() != 2 {
        return err(&bp, "expected [[x0,y0,z0],[x1,y1,z1]]");
    }
    let bounds = [vec3(&b[0], &bp.index(0))?, vec3(&b[1], &bp.index(1))?];
    if (0..3).any(|i| bounds[1][i] <= bounds[0][i]) {
        return err(&bp, "empty grid: each max must exceed its min");
    }
    let file = o.str("funcFile")?;
    let full = base_dir.map_or_else(|| Path::new(file).to_path_buf(), |d| d.join(file));
    let fp = root.key("funcFile");
    let text =
        crate::io::read_input_text(&full).or_else(|e| err(&fp, format!("cannot read {}: {e}", full.display())))?;
    let functions =
        load_function_list(&text, &full.display().to_string(), full.parent()).or_else(|e| err(&fp, e.to_string()))?;
    if functions.is_empty() {
        return err(&fp, "no functions");
    }
    Ok(Scene {
        grid: GridSpec { resolution: [n; 3], bounds, split: 5 },
        mode: Mode::Ia,
        names: (0..functions.len()).map(|i| i.to_string()).collect(),
        functions,
        regions: RegionRule::Identity,
        interest: Interest::all(),
        region_names: Default::default(),
    })
}
