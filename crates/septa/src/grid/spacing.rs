//! Whether a box grid's bounds and resolution give distinct, finite grid
//! vertices: bounds of +-1e308 have a width of infinity (every sampled
//! value then overflows, and the error blamed "function 0 at vertex 0"),
//! and 16 cubes over `[1e16, 1e16 + 8]` put several grid lines at one
//! double (coincident vertices: degenerate tets and polygons, exit 0).

/// Checks an axis of `n` cubes over `[lo, hi]` (finite, `lo < hi`) whose
/// grid line `i` is at `line(i)` (the box grid's `grid_coordinate`): the
/// width is finite and every grid line lies strictly above the one before.
/// The lines are monotone in their index (each step of the coordinate
/// rounds monotonically), so a spacing of a few ulps of the bounds'
/// magnitude is accepted at once and only a spacing near the doubles'
/// resolution is scanned line by line. The error says what goes wrong.
pub(crate) fn check_axis(lo: f64, hi: f64, n: usize, line: impl Fn(usize) -> f64) -> Result<(), String> {
    let width = hi - lo;
    if !width.is_finite() {
        return Err(format!("the width {width} overflows the doubles"));
    }
    let ulp = |x: f64| f64::from_bits(x.abs().to_bits() + 1) - x.abs();
    let scale = lo.abs().max(hi.abs());
    if width / n as f64 >= 8.0 * ulp(scale) {
        return Ok(());
    }
    let mut prev = line(0);
    for i in 1..=n {
        let x = line(i);
        if x <= prev {
            return Err(format!(
                "grid lines {} and {i} are both at {prev:e} (the spacing {:e} is below the doubles' resolution there)",
                i - 1,
                width / n as f64
            ));
        }
        prev = x;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::grid::{grid_coordinate, GridError};

    /// The box grid's check of axis `axis` (boxgrid.rs), as it reports it.
    fn check_axis(axis: usize, lo: f64, hi: f64, n: usize) -> Result<(), GridError> {
        super::check_axis(lo, hi, n, |i| grid_coordinate(lo, hi, i, n)).map_err(|reason| GridError::Spacing {
            axis,
            lo,
            hi,
            n,
            reason,
        })
    }

    #[test]
    fn spacing_must_be_representable() {
        assert!(check_axis(0, -1.0, 1.0, 1624).is_ok());
        assert!(check_axis(0, 0.0, 1e-300, 1000).is_ok());
        let e = check_axis(1, -1e308, 1e308, 4).unwrap_err().to_string();
        assert!(e.contains("axis 1") && e.contains("-1e308") && e.contains("overflows"), "{e}");
        // 1e16 has an ulp of 2: 16 cubes over a width of 8 put lines together
        let e = check_axis(2, 1e16, 1e16 + 8.0, 16).unwrap_err().to_string();
        assert!(e.contains("axis 2") && e.contains("grid lines"), "{e}");
        assert!(check_axis(2, 1e16, 1e16 + 8.0, 4).is_ok());
        // the smallest spacing accepted by the scan: every line distinct
        assert!(check_axis(0, 1.0, 1.0 + 64.0 * f64::EPSILON, 64).is_ok());
        assert!(check_axis(0, 1.0, 1.0 + 64.0 * f64::EPSILON, 65).is_err());
    }
}
