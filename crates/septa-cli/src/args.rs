//! Argument checks run by clap while parsing, so that every argument is
//! validated before any work starts (before: `septa demo --grid 0` ran
//! its first job before failing; `--block 0` panicked; `--explode nan`
//! wrote `v NaN NaN NaN`; `--threads 1000000` tried to start a million
//! threads). A bad value exits with code 2 and clap's message, which names
//! the argument and the accepted range.

/// Most worker threads accepted: far above any machine's cores, far below
/// what exhausts the process's thread limit.
pub const MAX_THREADS: usize = 1024;

/// Largest box grid resolution: `(n + 1)^3` grid vertices must have 32-bit
/// ids (`BoxGrid::new`), so `n + 1 <= 1625`.
pub const MAX_GRID: usize = 1624;

/// Most planes `septa cut --grid N` puts on each axis, and most random
/// planes: beyond these the plane arrangement alone (O(N^3) cut-cells for
/// a grid) exceeds any memory.
pub const MAX_CUT_PLANES: usize = 100_000;

fn parse_usize(s: &str) -> Result<usize, String> {
    s.trim().parse::<usize>().map_err(|_| format!("expected a whole number, not '{s}'"))
}

fn in_range(s: &str, lo: usize, hi: usize, why: &str) -> Result<usize, String> {
    let n = parse_usize(s)?;
    if n < lo || n > hi {
        return Err(format!("{n} is out of range {lo}..={hi}: {why}"));
    }
    Ok(n)
}

/// A box grid resolution: `1..=1624`.
pub fn grid(s: &str) -> Result<usize, String> {
    in_range(s, 1, MAX_GRID, "(N+1)^3 grid vertices need 32-bit ids")
}

/// Worker threads: `1..=1024`.
pub fn threads(s: &str) -> Result<usize, String> {
    in_range(s, 1, MAX_THREADS, "worker threads")
}

/// Worker threads where 0 means all cores: `0..=1024`.
pub fn threads_or_all(s: &str) -> Result<usize, String> {
    in_range(s, 0, MAX_THREADS, "worker threads, 0 for all cores")
}

/// A block edge in cubes: at least 1.
pub fn block(s: &str) -> Result<usize, String> {
    in_range(s, 1, MAX_GRID, "cubes per block edge")
}

/// A plane count of `septa cut`.
pub fn planes(s: &str) -> Result<usize, String> {
    in_range(s, 1, MAX_CUT_PLANES, "planes")
}

/// A finite number.
pub fn finite(s: &str) -> Result<f64, String> {
    let x: f64 = s.trim().parse().map_err(|_| format!("expected a number, not '{s}'"))?;
    if !x.is_finite() {
        return Err(format!("expected a finite number, not {x}"));
    }
    Ok(x)
}

/// A finite number `> 0` (a voxel size).
pub fn positive(s: &str) -> Result<f64, String> {
    let x = finite(s)?;
    if x <= 0.0 {
        return Err(format!("expected a number > 0, not {x}"));
    }
    Ok(x)
}

/// A finite number `>= 0`.
pub fn finite_nonneg(s: &str) -> Result<f64, String> {
    let x = finite(s)?;
    if x < 0.0 {
        return Err(format!("expected a number >= 0, not {x}"));
    }
    Ok(x)
}

/// A Gaussian sigma in voxels: 0 (no smoothing) or in `[1e-3, 1e6]`. Below
/// 1e-3 the kernel's weights at one voxel underflow to 0 (the blur is the
/// identity, so the value is surely a mistake); above 1e6 no volume is wide
/// enough for it to differ from a constant.
pub fn sigma(s: &str) -> Result<f64, String> {
    let x = finite_nonneg(s)?;
    if x != 0.0 && !(1e-3..=1e6).contains(&x) {
        return Err(format!("{x} is out of range: 0 (no smoothing) or 1e-3..=1e6 voxels"));
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges() {
        assert!(grid("0").is_err());
        assert!(grid("18446744073709551615").is_err());
        assert!(grid("18446744073709551616").is_err());
        assert_eq!(grid("1624"), Ok(1624));
        assert!(grid("1625").is_err());
        assert!(block("0").is_err());
        assert!(threads("1000000").is_err());
        assert_eq!(threads_or_all("0"), Ok(0));
        assert!(finite("nan").is_err() && finite("inf").is_err() && finite("-inf").is_err());
        assert_eq!(finite("-2.5"), Ok(-2.5));
        assert!(sigma("1e-300").is_err() && sigma("1e9").is_err());
        assert_eq!(sigma("0"), Ok(0.0));
        assert!(planes("18446744073709551615").is_err());
    }
}
