//! Memory estimates made before a large allocation, so that a job too big
//! for the machine is refused with the estimate and the way out instead of
//! aborting inside the allocator (before: `--grid 1000 --dense`, regions
//! at resolution 1600, `labels --sigma 1e9` all aborted with exit 134).
//!
//! The budget is the machine's available memory (`MemAvailable` of
//! `/proc/meminfo`), or `SEPTA_MEMORY_LIMIT` (bytes, or with a `K`/`M`/`G`
//! suffix) when set: tests set it to exercise the refusal on any machine.
//! An estimate is a lower bound of what the step allocates; refusing only
//! above the budget never refuses a job that would have fitted.

/// A job refused because its estimated memory exceeds the budget.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{what} needs at least {} but {} {}; {way_out}", human(*.needed), human(*.budget), .source_name)]
pub struct MemoryError {
    /// What would have been allocated (e.g. "sampling every vertex of the 1001^3 grid").
    pub what: String,
    /// Estimated bytes.
    pub needed: u64,
    /// Budget in bytes.
    pub budget: u64,
    /// Where the budget comes from ("is available", "is SEPTA_MEMORY_LIMIT").
    pub source_name: &'static str,
    /// How to run the job anyway (e.g. "drop --dense: the sparse path samples only active blocks").
    pub way_out: String,
}

/// Bytes as `12.3 GB` (powers of 1000, as people read them).
pub fn human(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e12 {
        format!("{:.1} TB", b / 1e12)
    } else if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else if b >= 1e6 {
        format!("{:.1} MB", b / 1e6)
    } else {
        format!("{bytes} bytes")
    }
}

/// The memory budget in bytes and where it comes from.
pub fn budget() -> (u64, &'static str) {
    if let Some(b) = std::env::var("SEPTA_MEMORY_LIMIT").ok().and_then(|s| parse_size(&s)) {
        return (b, "is SEPTA_MEMORY_LIMIT");
    }
    if let Some(b) = available() {
        return (b, "is available");
    }
    // No /proc (not Linux): only requests no allocator could satisfy are refused.
    (u64::MAX / 4, "is addressable")
}

/// A size in bytes, or with a `K`/`M`/`G` suffix (powers of 1024), as
/// `SEPTA_MEMORY_LIMIT` and `SEPTA_MAX_INPUT` are written.
pub fn parse_size(s: &str) -> Option<u64> {
    let s = s.trim();
    let (num, mul) = match s.chars().last()? {
        'K' | 'k' => (&s[..s.len() - 1], 1u64 << 10),
        'M' | 'm' => (&s[..s.len() - 1], 1 << 20),
        'G' | 'g' => (&s[..s.len() - 1], 1 << 30),
        _ => (s, 1),
    };
    num.trim().parse::<u64>().ok()?.checked_mul(mul)
}

/// `MemAvailable` plus free swap from `/proc/meminfo`.
fn available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let field = |name: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        let kb: u64 = line[name.len()..].trim().trim_end_matches("kB").trim().parse().ok()?;
        Some(kb * 1024)
    };
    Some(field("MemAvailable:")? + field("SwapFree:").unwrap_or(0))
}

/// Refuses `needed` bytes (saturating products are fine: an overflow means
/// "more than any budget") when they exceed the budget.
pub fn check(needed: u64, what: impl FnOnce() -> String, way_out: &str) -> Result<(), MemoryError> {
    let (budget, source_name) = budget();
    if needed <= budget {
        return Ok(());
    }
    Err(MemoryError { what: what(), needed, budget, source_name, way_out: way_out.to_string() })
}

/// Bytes the dense path allocates at least: every vertex position (3 x f64)
/// and `k` values (f64) per vertex, with one more value copy per function
/// while sampling. Saturates instead of overflowing.
pub fn dense_bytes(vertices: usize, k: usize) -> u64 {
    (vertices as u64).saturating_mul(24u64.saturating_add((k as u64).saturating_mul(16)))
}

/// [`check`] for sampling every vertex of a grid of `vertices` vertices with
/// `k` functions (the dense path).
pub fn check_dense(vertices: usize, k: usize, way_out: &str) -> Result<(), MemoryError> {
    check(
        dense_bytes(vertices, k),
        || format!("sampling {k} function(s) at every one of {vertices} grid vertices"),
        way_out,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_refusal() {
        assert_eq!(parse_size("2G"), Some(2 << 30));
        assert_eq!(parse_size("512"), Some(512));
        assert_eq!(parse_size("x"), None);
        assert_eq!(dense_bytes(usize::MAX, 3), u64::MAX);
        assert_eq!(dense_bytes(10, 1), 400);
        assert_eq!(human(64_000_000_000), "64.0 GB");
        // A request beyond any machine is refused whatever the budget source.
        let e = check(u64::MAX, || "x".into(), "use less").unwrap_err();
        assert!(e.to_string().contains("use less"), "{e}");
        assert!(check(1, || "x".into(), "").is_ok());
    }
}
