//! Scene errors that name the file, line and field, and the JSON path
//! machinery behind them.

use std::fmt;

/// One step of a JSON path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Seg {
    /// Object member.
    Key(String),
    /// Array element.
    Index(usize),
}

/// Path from the document root to a value, e.g. `functions[2].radius`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct JsonPath(pub Vec<Seg>);

impl JsonPath {
    /// This path extended by a member name.
    pub fn key(&self, k: &str) -> JsonPath {
        let mut v = self.0.clone();
        v.push(Seg::Key(k.to_string()));
        JsonPath(v)
    }
    /// This path extended by an array index.
    pub fn index(&self, i: usize) -> JsonPath {
        let mut v = self.0.clone();
        v.push(Seg::Index(i));
        JsonPath(v)
    }
}

impl fmt::Display for JsonPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return write!(f, "(document)");
        }
        for (i, s) in self.0.iter().enumerate() {
            match s {
                Seg::Key(k) if i == 0 => write!(f, "{k}")?,
                Seg::Key(k) => write!(f, ".{k}")?,
                Seg::Index(n) => write!(f, "[{n}]")?,
            }
        }
        Ok(())
    }
}

/// A problem in a scene: what is wrong and where.
///
/// Displayed as `FILE:LINE:COLUMN: PATH: MESSAGE`, e.g.
/// `part.json:7:19: functions[1].radius: negative radius -0.5`.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneError {
    /// File name (or `builtin:NAME`, or `<string>`).
    pub file: String,
    /// 1-based line, 0 when unknown.
    pub line: usize,
    /// 1-based column, 0 when unknown.
    pub column: usize,
    /// JSON path of the offending field.
    pub path: JsonPath,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}: {}: {}", self.file, self.line, self.column, self.path, self.message)
    }
}

impl std::error::Error for SceneError {}

/// An error before the file/line are known: a path and a message.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Located {
    pub path: JsonPath,
    pub message: String,
}

pub(crate) fn err<T>(path: &JsonPath, message: impl Into<String>) -> Result<T, Located> {
    Err(Located { path: path.clone(), message: message.into() })
}

/// Line and column (1-based) where the value at `path` starts in the JSON
/// `text`, or `None` if the path is not there. `text` must be valid JSON.
/// 1-based line and column of byte `offset` in `text`.
pub(crate) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, column)
}

/// Line and column of the value at `path` in TOML `text` (spans from
/// toml_edit's parse), or of the deepest part of it that exists.
pub(crate) fn locate_toml(text: &str, path: &JsonPath) -> Option<(usize, usize)> {
    use toml_edit::{ImDocument, Item, Table, Value};
    enum Node<'a> {
        Item(&'a Item),
        Table(&'a Table),
        Value(&'a Value),
    }
    let doc = ImDocument::parse(text).ok()?;
    let mut node = Node::Table(doc.as_table());
    let mut span = None;
    for seg in &path.0 {
        let next = match (seg, &node) {
            (Seg::Key(k), Node::Item(i)) => i.as_table_like().and_then(|t| t.get(k)).map(Node::Item),
            (Seg::Key(k), Node::Table(t)) => t.get(k).map(Node::Item),
            (Seg::Key(k), Node::Value(v)) => v.as_inline_table().and_then(|t| t.get(k)).map(Node::Value),
            (Seg::Index(n), Node::Item(i)) => match i.as_array_of_tables() {
                Some(a) => a.get(*n).map(Node::Table),
                None => i.as_array().and_then(|a| a.get(*n)).map(Node::Value),
            },
            (Seg::Index(n), Node::Value(v)) => v.as_array().and_then(|a| a.get(*n)).map(Node::Value),
            (Seg::Index(_), Node::Table(_)) => None,
        };
        let Some(next) = next else { break };
        span = match &next {
            Node::Item(i) => i.span(),
            Node::Table(t) => t.span(),
            Node::Value(v) => v.span(),
        }
        .or(span);
        node = next;
    }
    span.map(|s| line_column(text, s.start))
}

pub(crate) fn locate(text: &str, path: &JsonPath) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let mut pos = ws(b, 0);
    for seg in &path.0 {
        match seg {
            Seg::Key(k) => {
                if b.get(pos) != Some(&b'{') {
                    return None;
                }
                pos = ws(b, pos + 1);
                loop {
                    if b.get(pos) != Some(&b'"') {
                        return None;
                    }
                    let end = skip_string(b, pos)?;
                    let key: String = serde_json::from_str(&text[pos..end]).ok()?;
                    pos = ws(b, end);
                    if b.get(pos) != Some(&b':') {
                        return None;
                    }
                    pos = ws(b, pos + 1);
                    if &key == k {
                        break;
                    }
                    pos = ws(b, skip_value(b, pos)?);
                    if b.get(pos) != Some(&b',') {
                        return None;
                    }
                    pos = ws(b, pos + 1);
                }
            }
            Seg::Index(n) => {
                if b.get(pos) != Some(&b'[') {
                    return None;
                }
                pos = ws(b, pos + 1);
                for _ in 0..*n {
                    pos = ws(b, skip_value(b, pos)?);
                    if b.get(pos) != Some(&b',') {
                        return None;
                    }
                    pos = ws(b, pos + 1);
                }
                if b.get(pos) == Some(&b']') {
                    return None;
                }
            }
        }
    }
    let before = &text[..pos];
    let line = before.matches('\n').count() + 1;
    let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
    Some((line, column))
}

fn ws(b: &[u8], mut i: usize) -> usize {
    while i < b.len() && matches!(b[i], b' ' | b'\t' | b'\n' | b'\r') {
        i += 1;
    }
    i
}

/// Index just past the string starting at `i` (which is a quote).
fn skip_string(b: &[u8], mut i: usize) -> Option<usize> {
    i += 1;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            b'"' => return Some(i + 1),
            _ => i += 1,
        }
    }
    None
}

/// Index just past the value starting at `i`.
fn skip_value(b: &[u8], mut i: usize) -> Option<usize> {
    match *b.get(i)? {
        b'"' => skip_string(b, i),
        b'{' | b'[' => {
            let mut depth = 0usize;
            while i < b.len() {
                match b[i] {
                    b'"' => {
                        i = skip_string(b, i)?;
                        continue;
                    }
                    b'{' | b'[' => depth += 1,
                    b'}' | b']' => {
                        depth -= 1;
                        if depth == 0 {
                            return Some(i + 1);
                        }
                    }
                    _ => {}
                }
                i += 1;
            }
            None
        }
        _ => {
            while i < b.len() && !matches!(b[i], b',' | b'}' | b']' | b' ' | b'\n' | b'\t' | b'\r') {
                i += 1;
            }
            Some(i)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn locates_nested_values() {
        let text = "{\n  \"a\": [1, {\"b\": \"x,]\"},\n   {\"c\":\n 42}]\n}";
        let p = JsonPath::default().key("a").index(2).key("c");
        assert_eq!(locate(text, &p), Some((4, 2)));
        let p = JsonPath::default().key("a").index(1).key("b");
        assert_eq!(locate(text, &p), Some((2, 18)));
        assert_eq!(locate(text, &JsonPath::default().key("zz")), None);
        assert_eq!(p.to_string(), "a[1].b");
    }
}
