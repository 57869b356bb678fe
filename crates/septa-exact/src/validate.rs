//! Rejection of inputs on which no predicate is defined.

/// A NaN or infinite input value, with its position in the caller's array.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonFinite {
    /// Index of the first offending value in the slice given to [`check_finite`].
    pub index: usize,
    /// The offending value.
    pub value: f64,
}

impl std::fmt::Display for NonFinite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "value {} at index {} is not finite", self.value, self.index)
    }
}

impl std::error::Error for NonFinite {}

/// Checks that every value is finite; predicates assume it.
///
/// ```
/// assert!(septa_exact::check_finite(&[1.0, -2.5e300, 0.0]).is_ok());
/// let err = septa_exact::check_finite(&[1.0, f64::NAN]).unwrap_err();
/// assert_eq!(err.index, 1);
/// ```
pub fn check_finite(values: &[f64]) -> Result<(), NonFinite> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(NonFinite { index, value: values[index] }),
    }
}
