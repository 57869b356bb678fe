//! `septa labels --names FILE.json`: a name per label, `{"1": "liver",
//! "2": "kidney"}`, carried into every output that holds names (network.json
//! `names.regions`, the viewer, the summary and `--json`), as Python's
//! `septa.label_surfaces(volume, names={1: "liver"})` does.
use std::collections::BTreeMap;
use std::path::Path;

/// The label -> name table of `path`: a JSON object whose keys are integer
/// labels and whose values are non-empty names without control characters.
/// Errors name the file and the key.
pub fn read_label_names(path: &Path) -> Result<BTreeMap<i64, String>, String> {
    let file = path.display();
    let text = septa::io::read_input_text(path).map_err(|e| format!("--names {file}: {e}"))?;
    let doc = septa::scene::parse_json_strict(&text).map_err(|e| format!("--names {file}: {e}"))?;
    let serde_json::Value::Object(map) = doc else {
        return Err(format!("--names {file}: expected an object of label -> name, like {{\"1\": \"liver\"}}"));
    };
    let mut out = BTreeMap::new();
    for (key, value) in map {
        let label: i64 = key
            .trim()
            .parse()
            .ok()
            .filter(|_| !key.is_empty() && key.trim() == key)
            .ok_or_else(|| format!("--names {file}: key {key:?} is not an integer label"))?;
        let name = match value {
            serde_json::Value::String(s) if !s.trim().is_empty() && !s.chars().any(char::is_control) => s,
            other => {
                return Err(format!(
                    "--names {file}: label {label}: the name must be a non-empty text without control characters, not {other}"
                ))
            }
        };
        out.insert(label, name);
    }
    Ok(out)
}
