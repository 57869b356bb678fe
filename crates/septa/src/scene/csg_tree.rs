//! CSG trees in the adaptive-grid paper's format (its `--tree` files): a
//! JSON list of nodes `{"type": "Intersection" | "Union" | "Negation",
//! "elements": [a, b]}`. Node 1 is the root; an element `k > 0` is node
//! `k` (1-based), `-k` is function `k` (1-based) of the function file, and
//! a `Negation` uses only its first element (the second is 0).
//!
//! Sign convention: by default Septa's, positive inside. A function is
//! "in" where it is positive, `Intersection` is in where both are, `Union`
//! where either is, `Negation` where its operand is not.
//!
//! The paper's program evaluates `Intersection` as `max` and `Union` as
//! `min` of the values and calls the result's negative side inside: a leaf
//! is in where its function is *negative*, although its functions are
//! positive inside. The trees of its figures are written for that reading
//! (Figure 1's cube is six planes with outward normals intersected, and its
//! sphere and cylinders are negated to make them negative inside), so read
//! them with `negative_inside` to get the paper's shapes; read with the
//! default, Figure 1's tree is empty (above one face and below the
//! opposite one at once). Both readings are exact: only the leaves' sign
//! differs.

use std::collections::HashMap;

use serde_json::Value;

use super::error::{err, locate, JsonPath, Located, SceneError};
use super::region_rule::Expr;
use super::spec::{array, Obj};

/// Read a CSG tree file's text into an [`Expr`] over `n_functions`
/// functions; errors name the file, line and node.
///
/// ```
/// use septa::scene::{load_csg_tree, Expr};
/// let t = r#"[{"type": "Intersection", "elements": [-1, 2]},
///             {"type": "Negation", "elements": [-2, 0]}]"#;
/// let e = load_csg_tree(t, "tree.json", 2, false).unwrap();
/// assert!(e.eval(&|i| i == 0)); // inside 1 (positive), outside 2
/// assert!(!e.eval(&|_| true));
/// // The paper's program's reading: in where a function is negative.
/// let n = load_csg_tree(t, "tree.json", 2, true).unwrap();
/// assert!(n.eval(&|i| i == 1));
/// ```
pub fn load_csg_tree(text: &str, file: &str, n_functions: usize, negative_inside: bool) -> Result<Expr, SceneError> {
    let v: Value = super::strict_json::parse(text).map_err(|e| SceneError {
        file: file.to_string(),
        line: e.line(),
        column: e.column(),
        path: JsonPath::default(),
        message: e.to_string(),
    })?;
    csg_tree(&v, &JsonPath::default(), n_functions, negative_inside).map_err(|l| {
        let (line, column) = locate(text, &l.path).unwrap_or((0, 0));
        SceneError { file: file.to_string(), line, column, path: l.path, message: l.message }
    })
}

/// The tree `v` (a list of nodes) as an expression.
pub(crate) fn csg_tree(v: &Value, path: &JsonPath, n_functions: usize, negative_inside: bool) -> Result<Expr, Located> {
    let nodes = array(v, path)?;
    if nodes.is_empty() {
        return err(path, "an empty CSG tree (node 1 is the root)");
    }
    let mut done: HashMap<usize, (Expr, usize)> = HashMap::new();
    let mut open = vec![false; nodes.len()];
    let ctx = Tree { nodes, path, n: n_functions, negative_inside, made: std::cell::Cell::new(0) };
    node(&ctx, 1, 0, &mut done, &mut open).map(|(e, _)| e)
}

/// The deepest CSG tree read (every walk of the expression recurses once
/// per level, so a chain of a million nodes would overflow the stack).
pub const MAX_TREE_DEPTH: usize = 1024;

/// The most expression nodes a CSG tree may expand to: a node used twice is
/// copied, so forty nodes each naming the next twice would make 2^40.
pub const MAX_TREE_NODES: usize = 1 << 20;

struct Tree<'a> {
    nodes: &'a [Value],
    path: &'a JsonPath,
    n: usize,
    negative_inside: bool,
    /// Expression nodes made so far (copies of shared nodes included).
    made: std::cell::Cell<usize>,
}

/// Node `k` (1-based) at `depth` as an expression and its size in nodes.
fn node(
    t: &Tree,
    k: usize,
    depth: usize,
    done: &mut HashMap<usize, (Expr, usize)>,
    open: &mut [bool],
) -> Result<(Expr, usize), Located> {
    let (nodes, path, n) = (t.nodes, t.path, t.n);
    let grow = |by: usize| -> Result<(), Located> {
        t.made.set(t.made.get().saturating_add(by));
        if t.made.get() > MAX_TREE_NODES {
            return err(
                path,
                format!("the tree expands to more than {MAX_TREE_NODES} nodes (shared nodes are copied)"),
            );
        }
        Ok(())
    };
    if let Some((e, size)) = done.get(&k) {
        grow(*size)?;
        return Ok((e.clone(), *size));
    }
    let p = path.index(k - 1);
    if open[k - 1] {
        return err(&p, format!("node {k} contains itself (a cycle in the tree)"));
    }
    open[k - 1] = true;
    // every walk of the tree recurses once per level: a chain of nodes
    // deeper than the limit is an error, not a stack overflow
    if depth > MAX_TREE_DEPTH {
        return err(&p, format!("the tree is nested deeper than {MAX_TREE_DEPTH} levels"));
    }
    let o = Obj::new(&nodes[k - 1], &p)?;
    o.mark_all(&["type", "elements"]);
    o.finish()?;
    let ty = o.str("type")?;
    let ep = p.key("elements");
    let el = array(o.get("elements")?, &ep)?;
    let mut size = 1;
    let mut operand = |i: usize| -> Result<Expr, Located> {
        let Some(x) = el.get(i) else { return err(&ep, "expected 2 elements") };
        let ip = ep.index(i);
        match x.as_i64() {
            Some(f) if f < 0 && (-f) as usize <= n => {
                let leaf = Expr::Func((-f) as usize - 1);
                size += 2;
                grow(2)?;
                Ok(if t.negative_inside { Expr::Not(Box::new(leaf)) } else { leaf })
            }
            Some(f) if f < 0 => err(&ip, format!("function {} does not exist ({n} functions)", -f)),
            Some(c) if c > 0 && (c as usize) <= nodes.len() => {
                let (e, s) = node(t, c as usize, depth + 1, done, open)?;
                size += s;
                Ok(e)
            }
            Some(c) if c > 0 => err(&ip, format!("node {c} does not exist ({} nodes)", nodes.len())),
            _ => err(&ip, "an element is a node number (1-based) or minus a function number"),
        }
    };
    let e = match ty {
        "Intersection" | "intersection" => Expr::And(vec![operand(0)?, operand(1)?]),
        "Union" | "union" => Expr::Or(vec![operand(0)?, operand(1)?]),
        "Negation" | "negation" => Expr::Not(Box::new(operand(0)?)),
        other => {
            return err(&p.key("type"), format!("unknown CSG operation `{other}` (Intersection, Union, Negation)"))
        }
    };
    if el.len() != 2 {
        return err(&ep, format!("expected 2 elements, got {}", el.len()));
    }
    open[k - 1] = false;
    grow(1)?;
    done.insert(k, (e.clone(), size));
    Ok((e, size))
}
