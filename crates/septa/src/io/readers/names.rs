//! Names of a result's functions and regions (or labels, or materials), as
//! a scene file gives them (`"name"` of a function, `"region_names"`) or a
//! label table (`septa labels --names`, NIfTI/NRRD label descriptions).
//! Every writer names things by these where it can: the summary, `network.json`
//! and `network.npz` (`names`), OBJ groups, Gmsh physical names, the viewer.

use std::collections::BTreeMap;

/// Function and region names of one result (both may be empty).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Names {
    /// Per function, its name (a scene names unnamed functions by index).
    pub functions: Vec<String>,
    /// Region (regions), label (label volumes) or material (MI) -> name.
    pub regions: BTreeMap<i64, String>,
}

impl Names {
    /// Function `f`'s name, else its index.
    pub fn function(&self, f: usize) -> String {
        self.functions.get(f).cloned().unwrap_or_else(|| f.to_string())
    }

    /// Region `r`'s name, if it has one.
    pub fn region(&self, r: i64) -> Option<&str> {
        self.regions.get(&r).map(String::as_str)
    }

    /// Region `r` in words: `3 (liver)`, or `3`.
    pub fn region_text(&self, r: i64) -> String {
        match self.region(r) {
            Some(n) => format!("{r} ({n})"),
            None => r.to_string(),
        }
    }

    /// `{"functions": [..], "regions": {"r": name, ..}}` (keys as text: JSON object keys).
    pub fn to_json(&self) -> serde_json::Value {
        let regions: serde_json::Map<String, serde_json::Value> =
            self.regions.iter().map(|(k, v)| (k.to_string(), v.clone().into())).collect();
        serde_json::json!({"functions": self.functions, "regions": regions})
    }

    /// Patch `p` (labels `[a, b]`) by name, as its OBJ group and Gmsh
    /// physical name: `patch_<p>_<a>_<b>` with its labels' names (IA:
    /// `patch_<p>_<f>`, its function's name; MI materials by their region or
    /// function name; regions and labels by theirs), a label without a name
    /// by its id; `patch_<p>_labels_<a>_<b>` when neither has a name (a
    /// scene's unnamed function is named by its index: no name).
    pub fn patch_name(&self, mode: &str, p: usize, [a, b]: [i32; 2]) -> String {
        let function = |f: i32| usize::try_from(f).ok().and_then(|f| self.functions.get(f));
        let real = |n: Option<&String>, x: i32| n.filter(|n| **n != x.to_string()).map(|n| name_token(n));
        if mode == "ia" && (b < 0 || a == b) {
            return match real(function(a), a) {
                Some(n) => format!("patch_{p}_{n}"),
                None => format!("patch_{p}_labels_{a}_{b}"),
            };
        }
        let named = |x: i32| {
            let n = self.regions.get(&(x as i64)).or(if mode == "mi" { function(x) } else { None });
            real(n, x)
        };
        match (named(a), named(b)) {
            (None, None) => format!("patch_{p}_labels_{a}_{b}"),
            (na, nb) => format!("patch_{p}_{}_{}", na.unwrap_or(a.to_string()), nb.unwrap_or(b.to_string())),
        }
    }

    /// Whether there is no name at all.
    pub fn is_empty(&self) -> bool {
        self.functions.is_empty() && self.regions.is_empty()
    }
}

/// A name made safe for an OBJ group or a Gmsh physical name: letters,
/// digits, `_`, `-` and `.` kept, anything else (spaces, quotes) as `_`.
pub fn name_token(s: &str) -> String {
    s.chars().map(|c| if c.is_alphanumeric() || matches!(c, '_' | '-' | '.') { c } else { '_' }).collect()
}
