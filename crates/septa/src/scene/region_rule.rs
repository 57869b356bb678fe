//! Region rules (Bloomenthal 4.2 and 4.8): a cell of the arrangement is
//! mapped to an integer **region** from its label alone: its sign vector
//! in IA mode (one sign per function; a 3D cell never has a zero sign) or
//! its material (the function that is largest) in MI mode.
//!
//! A rule is an ordered list of conditions, first match wins, exactly
//! Bloomenthal's `Region(p)` form; each condition is a CSG expression over
//! the functions (a function name means "the function is positive" in IA
//! and "this function's material" in MI). `surfaces` are the region pairs
//! of interest and `curves` the region triples of interest. All of this
//! is pure functions on labels.

use std::collections::BTreeSet;

/// A region value (Bloomenthal's integer `f_reg`).
pub type RegionId = i64;

/// CSG / boolean expression over the functions of a scene.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Expr {
    /// Always true.
    True,
    /// Function `i` (by index) is positive (IA) or is the material (MI).
    Func(usize),
    /// Complement.
    Not(Box<Expr>),
    /// Intersection (all).
    And(Vec<Expr>),
    /// Union (any).
    Or(Vec<Expr>),
    /// Difference `a - b` (in `a` and not in `b`).
    Diff(Box<Expr>, Box<Expr>),
}

impl Expr {
    /// Evaluate with `atom(i)` the truth of function `i`.
    pub fn eval(&self, atom: &impl Fn(usize) -> bool) -> bool {
        match self {
            Expr::True => true,
            Expr::Func(i) => atom(*i),
            Expr::Not(e) => !e.eval(atom),
            Expr::And(v) => v.iter().all(|e| e.eval(atom)),
            Expr::Or(v) => v.iter().any(|e| e.eval(atom)),
            Expr::Diff(a, b) => a.eval(atom) && !b.eval(atom),
        }
    }

    /// Parse the text form. Operators, loosest first: `-` (difference,
    /// left-associative), `|` (union), `&` (intersection), `!` (complement),
    /// and parentheses. `resolve` maps a name (letters, digits, `_`, `.`)
    /// to a function index; unnamed functions are named by their index.
    ///
    /// ```
    /// use septa::scene::Expr;
    /// let names = ["plate", "boss", "hole"];
    /// let e = Expr::parse("plate | boss - hole", &|n: &str| names.iter().position(|x| *x == n)).unwrap();
    /// // (plate | boss) - hole
    /// assert!(e.eval(&|i| i == 1));
    /// assert!(!e.eval(&|i| i == 1 || i == 2));
    /// ```
    ///
    /// Limits (a clear error instead of a crash on hostile text): at most
    /// [`MAX_RULE_LEN`] characters and [`MAX_DEPTH`] levels of `!` and
    /// parentheses; `a - b - c` is read as `a - (b | c)`, the same set,
    /// so a long chain of differences stays flat.
    pub fn parse(text: &str, resolve: &impl Fn(&str) -> Option<usize>) -> Result<Expr, String> {
        if text.len() > MAX_RULE_LEN {
            return Err(format!(
                "a condition of {} bytes is longer than the limit of {MAX_RULE_LEN} (name the parts as functions)",
                text.len()
            ));
        }
        let toks = tokenize(text)?;
        let mut p = Parser { toks, pos: 0, resolve, depth: 0 };
        let e = p.diff()?;
        if p.pos != p.toks.len() {
            return Err(format!("unexpected `{}` in `{text}`", p.toks[p.pos]));
        }
        Ok(e)
    }

    /// Every function index the expression mentions.
    pub fn functions(&self, out: &mut BTreeSet<usize>) {
        match self {
            Expr::True => {}
            Expr::Func(i) => {
                out.insert(*i);
            }
            Expr::Not(e) => e.functions(out),
            Expr::And(v) | Expr::Or(v) => v.iter().for_each(|e| e.functions(out)),
            Expr::Diff(a, b) => {
                a.functions(out);
                b.functions(out);
            }
        }
    }
}

fn tokenize(text: &str) -> Result<Vec<String>, String> {
    let mut toks = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
        } else if "()|&-!".contains(c) {
            toks.push(c.to_string());
            chars.next();
        } else if c.is_alphanumeric() || c == '_' || c == '.' {
            let mut s = String::new();
            while let Some(&c) = chars.peek() {
                if c.is_alphanumeric() || c == '_' || c == '.' {
                    s.push(c);
                    chars.next();
                } else {
                    break;
                }
            }
            toks.push(s);
        } else {
            return Err(format!("unexpected character `{c}` in `{text}`"));
        }
    }
    if toks.is_empty() {
        return Err("empty expression".into());
    }
    Ok(toks)
}

/// The longest condition text [`Expr::parse`] reads, in bytes.
pub const MAX_RULE_LEN: usize = 1 << 16;

/// The deepest nesting of `!` and parentheses [`Expr::parse`] reads (the
/// parser and every walk of the tree recurse once per level).
pub const MAX_DEPTH: usize = 256;

struct Parser<'a, F> {
    toks: Vec<String>,
    pos: usize,
    resolve: &'a F,
    /// Levels of `!` and `(` open at `pos`.
    depth: usize,
}

impl<F: Fn(&str) -> Option<usize>> Parser<'_, F> {
    fn peek(&self) -> Option<&str> {
        self.toks.get(self.pos).map(|s| s.as_str())
    }
    fn diff(&mut self) -> Result<Expr, String> {
        let e = self.or()?;
        let mut minus = Vec::new();
        while self.peek() == Some("-") {
            self.pos += 1;
            minus.push(self.or()?);
        }
        Ok(difference(e, minus))
    }
    /// One more level of `!` or `(`, refused beyond [`MAX_DEPTH`].
    fn deeper(&mut self) -> Result<(), String> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(format!("nested deeper than {MAX_DEPTH} levels of `!` and parentheses"));
        }
        Ok(())
    }
    fn or(&mut self) -> Result<Expr, String> {
        let mut v = vec![self.and()?];
        while self.peek() == Some("|") {
            self.pos += 1;
            v.push(self.and()?);
        }
        Ok(if v.len() == 1 { v.pop().unwrap() } else { Expr::Or(v) })
    }
    fn and(&mut self) -> Result<Expr, String> {
        let mut v = vec![self.not()?];
        while self.peek() == Some("&") {
            self.pos += 1;
            v.push(self.not()?);
        }
        Ok(if v.len() == 1 { v.pop().unwrap() } else { Expr::And(v) })
    }
    fn not(&mut self) -> Result<Expr, String> {
        match self.peek() {
            Some("!") => {
                self.pos += 1;
                self.deeper()?;
                let e = Expr::Not(Box::new(self.not()?));
                self.depth -= 1;
                Ok(e)
            }
            Some("(") => {
                self.pos += 1;
                self.deeper()?;
                let e = self.diff()?;
                if self.peek() != Some(")") {
                    return Err("missing `)`".into());
                }
                self.pos += 1;
                self.depth -= 1;
                Ok(e)
            }
            Some(t) if !"|&-)".contains(t) => {
                let name = t.to_string();
                self.pos += 1;
                match (self.resolve)(&name) {
                    Some(i) => Ok(Expr::Func(i)),
                    None => Err(format!("unknown function `{name}`")),
                }
            }
            Some(t) => Err(format!("unexpected `{t}`")),
            None => Err("expression ends early".into()),
        }
    }
}

/// `a - b1 - b2 - ...` as `a - (b1 | b2 | ...)`: the same set, one level
/// deep however many are taken away.
pub(crate) fn difference(a: Expr, mut minus: Vec<Expr>) -> Expr {
    match minus.len() {
        0 => a,
        1 => Expr::Diff(Box::new(a), Box::new(minus.pop().expect("one"))),
        _ => Expr::Diff(Box::new(a), Box::new(Expr::Or(minus))),
    }
}

/// One rule: `when` holds (or always, if none) gives `region`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rule {
    /// Condition; `Expr::True` for a catch-all.
    pub when: Expr,
    /// Region given when the condition holds.
    pub region: RegionId,
}

/// Maps a cell label to a region.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RegionRule {
    /// No rule: IA regions are sign vectors (bit `j` set when function
    /// `j` is positive; at most 62 functions), MI regions are materials.
    Identity,
    /// Ordered rules, first match wins; `otherwise` when none matches.
    Rules {
        /// The rules in order.
        rules: Vec<Rule>,
        /// Region of a cell that no rule matches.
        otherwise: RegionId,
    },
}

impl RegionRule {
    /// A solid from a CSG expression: region 1 inside, 0 outside.
    pub fn solid(e: Expr) -> RegionRule {
        RegionRule::Rules { rules: vec![Rule { when: e, region: 1 }], otherwise: 0 }
    }

    fn first_match(&self, atom: impl Fn(usize) -> bool) -> Option<RegionId> {
        match self {
            RegionRule::Identity => None,
            RegionRule::Rules { rules, otherwise } => {
                Some(rules.iter().find(|r| r.when.eval(&atom)).map_or(*otherwise, |r| r.region))
            }
        }
    }

    /// Region of an IA cell with `positive[j]` the sign of function `j`.
    ///
    /// ```
    /// use septa::scene::{Expr, RegionRule, Rule};
    /// // Bloomenthal 4.8.2: inside small sphere (f0) -> 1, large (f1) -> 2, else 0.
    /// let r = RegionRule::Rules { rules: vec![
    ///     Rule { when: Expr::Func(0), region: 1 },
    ///     Rule { when: Expr::Func(1), region: 2 }], otherwise: 0 };
    /// assert_eq!(r.region_ia(&[true, true]), 1);
    /// assert_eq!(r.region_ia(&[false, true]), 2);
    /// assert_eq!(r.region_ia(&[false, false]), 0);
    /// ```
    pub fn region_ia(&self, positive: &[bool]) -> RegionId {
        self.first_match(|i| positive.get(i).copied().unwrap_or(false)).unwrap_or_else(|| {
            positive.iter().take(62).enumerate().fold(0, |m, (j, &s)| if s { m | (1 << j) } else { m })
        })
    }

    /// Region of an MI cell whose material is function `material`.
    pub fn region_mi(&self, material: usize) -> RegionId {
        self.first_match(|i| i == material).unwrap_or(material as RegionId)
    }

    /// Every region a rule can give (none for [`RegionRule::Identity`]).
    pub fn regions(&self) -> BTreeSet<RegionId> {
        match self {
            RegionRule::Identity => BTreeSet::new(),
            RegionRule::Rules { rules, otherwise } => rules.iter().map(|r| r.region).chain([*otherwise]).collect(),
        }
    }
}

/// Region pairs and triples of interest (Bloomenthal 4.2, 4.8), and
/// whether feature curves (sharp edges) are wanted.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Interest {
    /// Region pairs whose separating surfaces are wanted, each sorted;
    /// `None` means every pair.
    pub surfaces: Option<BTreeSet<(RegionId, RegionId)>>,
    /// Region triples whose meeting curves are wanted, each sorted, in
    /// the order given; `None` means every triple (an edge's curve is then
    /// that of the three least regions around it).
    pub curves: Option<Vec<[RegionId; 3]>>,
    /// Feature curves: where a kept surface between two regions changes the
    /// function it lies on (the sharp edges of a CSG solid; `regions/features.rs`).
    pub features: bool,
}

impl Default for Interest {
    /// Every surface, every triple's curve and the feature curves.
    fn default() -> Interest {
        Interest { surfaces: None, curves: None, features: true }
    }
}

impl Interest {
    /// Every surface, every triple's curve and the feature curves.
    pub fn all() -> Interest {
        Interest::default()
    }

    /// From lists of pairs and triples (order inside each does not matter);
    /// feature curves too.
    pub fn new(surfaces: Option<&[[RegionId; 2]]>, curves: &[[RegionId; 3]]) -> Interest {
        Interest {
            surfaces: surfaces.map(|s| s.iter().map(|&[a, b]| (a.min(b), a.max(b))).collect()),
            curves: Some(
                curves
                    .iter()
                    .map(|c| {
                        let mut c = *c;
                        c.sort();
                        c
                    })
                    .collect(),
            ),
            features: true,
        }
    }

    /// True when the patch between regions `a` and `b` is kept: the regions
    /// differ (patches inside one region are dropped) and the pair is of
    /// interest.
    pub fn surface(&self, a: RegionId, b: RegionId) -> bool {
        a != b
            && match &self.surfaces {
                None => true,
                Some(s) => s.contains(&(a.min(b), a.max(b))),
            }
    }

    /// The first triple of interest whose three regions all occur among
    /// `around` (the regions of the cells around a chain, sorted), if any.
    /// With every triple of interest, the three least of `around` (sorted).
    pub fn curve(&self, around: &[RegionId]) -> Option<[RegionId; 3]> {
        match &self.curves {
            None => (around.len() >= 3).then(|| [around[0], around[1], around[2]]),
            Some(list) => list.iter().find(|t| t.iter().all(|r| around.contains(r))).copied(),
        }
    }
}

/// Orientation rule (Bloomenthal 4.5.2.4): a polygon separating regions
/// `a` and `b` is ordered counter-clockwise seen from the lesser region,
/// i.e. its right-hand normal points into `min(a, b)`. Given the region the
/// polygon's current normal points into, returns true when the polygon
/// must be reversed.
///
/// ```
/// use septa::scene::must_flip;
/// assert!(!must_flip(1, 3)); // normal into 1, the lesser: keep
/// assert!(must_flip(3, 1));
/// ```
pub fn must_flip(normal_into: RegionId, other: RegionId) -> bool {
    normal_into > other
}
