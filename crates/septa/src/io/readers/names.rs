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
