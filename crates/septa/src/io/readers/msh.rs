//! Gmsh `.msh` tet meshes, ASCII formats 2.2 and 4.1: nodes and 4-node
//! tetrahedra (element type 4); other elements are ignored. Node tags are
//! mapped to 0-based vertex ids in the order the nodes appear.

use std::collections::HashMap;
use std::path::Path;

use crate::io::readers::functions::MeshData;

/// Why a `.msh` file could not be read; names the line.
#[derive(Debug, thiserror::Error)]
pub enum MshError {
    /// File system error.
    #[error("{path}: {source}")]
    Io {
        /// File.
        path: String,
        /// Cause.
        source: std::io::Error,
    },
    /// Bad content.
    #[error("{path}:{line}: {message}")]
    Format {
        /// File.
        path: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

struct Lines<'a> {
    it: std::iter::Enumerate<std::str::Lines<'a>>,
    line: usize,
    path: String,
}

impl<'a> Lines<'a> {
    fn next(&mut self) -> Result<&'a str, MshError> {
        match self.it.next() {
            Some((i, l)) => {
                self.line = i + 1;
                Ok(l.trim())
            }
            None => Err(self.err("unexpected end of file")),
        }
    }
    fn err(&self, m: impl Into<String>) -> MshError {
        MshError::Format { path: self.path.clone(), line: self.line, message: m.into() }
    }
    fn nums<T: std::str::FromStr>(&mut self) -> Result<Vec<T>, MshError> {
        let l = self.next()?;
        l.split_whitespace().map(|t| t.parse().map_err(|_| self.err(format!("'{t}' is not a number")))).collect()
    }
    /// The first number of the next line (an error naming the line if it has none).
    fn num<T: std::str::FromStr>(&mut self) -> Result<T, MshError> {
        let v = self.nums::<T>()?;
        v.into_iter().next().ok_or_else(|| self.err("a number was expected"))
    }
}

/// Records node `tag` as vertex `id`; a tag given twice is an error naming
/// both lines' tag (before: the later node silently won).
fn new_node(ls: &Lines, tag_to_id: &mut HashMap<i64, i64>, tag: i64, id: usize) -> Result<(), MshError> {
    match tag_to_id.insert(tag, id as i64) {
        Some(first) => Err(ls.err(format!("node tag {tag} is given twice (as vertex {first} and again here)"))),
        None => Ok(()),
    }
}

/// Reads the vertices and tets of a Gmsh `.msh` (2.2 or 4.1, ASCII).
pub fn read_msh(path: &Path) -> Result<MeshData, MshError> {
    let p = path.display().to_string();
    let text =
        crate::io::files::input::read_input_text(path).map_err(|source| MshError::Io { path: p.clone(), source })?;
    parse_msh(&text, &p)
}

/// Parses `.msh` text; `path` names the source in errors.
pub fn parse_msh(text: &str, path: &str) -> Result<MeshData, MshError> {
    let mut ls = Lines { it: text.lines().enumerate(), line: 0, path: path.to_string() };
    let mut version = 0.0f64;
    let mut vertices = Vec::new();
    let mut tag_to_id: HashMap<i64, i64> = HashMap::new();
    let mut tets = Vec::new();
    let mut pending_tets: Vec<([i64; 4], usize)> = Vec::new();
    while let Some((i, l)) = ls.it.next() {
        ls.line = i + 1;
        let l = l.trim();
        match l {
            "$MeshFormat" => {
                let f: Vec<String> = ls.next()?.split_whitespace().map(String::from).collect();
                version = f.first().and_then(|v| v.parse().ok()).ok_or_else(|| ls.err("bad $MeshFormat"))?;
                if f.get(1).map(String::as_str) != Some("0") {
                    return Err(ls.err("binary .msh is not supported; save as ASCII"));
                }
                if !(version == 2.2 || (4.0..4.2).contains(&version)) {
                    return Err(ls.err(format!("msh version {version} is not supported (2.2 or 4.1)")));
                }
            }
            "$Nodes" if version < 3.0 => {
                let n = ls.num::<usize>()?;
                for _ in 0..n {
                    let v = ls.nums::<f64>()?;
                    if v.len() < 4 {
                        return Err(ls.err("node line needs: tag x y z"));
                    }
                    if v[0].fract() != 0.0 || !(1.0..9.0e15).contains(&v[0]) {
                        return Err(ls.err(format!("node tag {} is not a positive whole number", v[0])));
                    }
                    new_node(&ls, &mut tag_to_id, v[0] as i64, vertices.len())?;
                    vertices.push([v[1], v[2], v[3]]);
                }
            }
            "$Nodes" => {
                let h = ls.nums::<usize>()?;
                let blocks = *h.first().ok_or_else(|| ls.err("bad $Nodes header"))?;
                for _ in 0..blocks {
                    let b = ls.nums::<i64>()?;
                    if b.len() < 4 {
                        return Err(ls.err("bad node block header"));
                    }
                    if b[2] != 0 {
                        return Err(ls.err("parametric nodes are not supported"));
                    }
                    let n = b[3] as usize;
                    // Counts come from the file: never reserve on their word.
                    let mut tags = Vec::new();
                    for _ in 0..n {
                        tags.push(ls.num::<i64>()?);
                    }
                    for tag in tags {
                        let v = ls.nums::<f64>()?;
                        if v.len() < 3 {
                            return Err(ls.err("node coordinates need x y z"));
                        }
                        new_node(&ls, &mut tag_to_id, tag, vertices.len())?;
                        vertices.push([v[0], v[1], v[2]]);
                    }
                }
            }
            "$Elements" if version < 3.0 => {
                let n = ls.num::<usize>()?;
                for _ in 0..n {
                    let e = ls.nums::<i64>()?;
                    if e.len() < 3 {
                        return Err(ls.err("element line too short"));
                    }
                    if e[1] == 4 {
                        let nodes = usize::try_from(e[2])
                            .ok()
                            .and_then(|tags| e.get(3 + tags.min(e.len())..).and_then(|n| n.get(..4)))
                            .ok_or_else(|| ls.err("tet needs 4 nodes"))?;
                        pending_tets.push(([nodes[0], nodes[1], nodes[2], nodes[3]], ls.line));
                    }
                }
            }
            "$Elements" => {
                let h = ls.nums::<usize>()?;
                let blocks = *h.first().ok_or_else(|| ls.err("bad $Elements header"))?;
                for _ in 0..blocks {
                    let b = ls.nums::<i64>()?;
                    if b.len() < 4 {
                        return Err(ls.err("bad element block header"));
                    }
                    for _ in 0..b[3] {
                        let e = ls.nums::<i64>()?;
                        if b[2] == 4 {
                            if e.len() < 5 {
                                return Err(ls.err("tet needs 4 nodes"));
                            }
                            pending_tets.push(([e[1], e[2], e[3], e[4]], ls.line));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    for (t, line) in pending_tets {
        let mut ids = [0i64; 4];
        for j in 0..4 {
            ids[j] = *tag_to_id.get(&t[j]).ok_or_else(|| MshError::Format {
                path: path.to_string(),
                line,
                message: format!("tet refers to node {} which does not exist", t[j]),
            })?;
        }
        tets.push(ids);
    }
    if version == 0.0 {
        return Err(MshError::Format { path: path.to_string(), line: 1, message: "no $MeshFormat section".into() });
    }
    Ok((vertices, tets))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_both_versions() {
        let v22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n7 0 0 1\n$EndNodes\n\
                   $Elements\n2\n1 15 2 0 1 1\n2 4 2 0 1 1 2 3 7\n$EndElements\n";
        let (v, t) = parse_msh(v22, "a.msh").unwrap();
        assert_eq!(v.len(), 4);
        assert_eq!(t, vec![[0, 1, 2, 3]]);
        let v41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n\
                   $Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4\n$EndElements\n";
        let (v, t) = parse_msh(v41, "b.msh").unwrap();
        assert_eq!(v[3], [0.0, 0.0, 1.0]);
        assert_eq!(t, vec![[0, 1, 2, 3]]);
        let bad = v22.replace("1 2 3 7", "1 2 3 9");
        let e = parse_msh(&bad, "c.msh").unwrap_err().to_string();
        assert!(e.contains("c.msh:14") && e.contains("node 9"), "{e}");
    }
}
